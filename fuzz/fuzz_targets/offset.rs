//! The offsetter (seed 003) on shapes decoded from the fuzzer's bytes: every result must pass
//! `offset::check::problems` (closed, no self-crossings, oriented, at the distance, covering
//! exactly the offset region). Failures shrunk by the fuzzer are kept in
//! tests/fuzz_regressions/offset-*.bin and replayed by tests/offset.rs.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf::geom::Tolerances;
use swarf::offset::check::{problems, shape_from_bytes};
use swarf::offset::offset;

fuzz_target!(|data: &[u8]| {
    if let Some((shape, d)) = shape_from_bytes(data) {
        let out = offset(&shape, d, &Tolerances::DEFAULT);
        let p = problems(&shape, d, &out, 1e-6, 4);
        assert!(p.is_empty(), "offset by {d}: {p:?}");
    }
});
