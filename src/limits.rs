//! The limits every input is held to, in one place: what a file or a job may ask for before
//! swarf refuses it with a message naming the file's element or the job's field (and, for a
//! count of work, the setting to change). None of them limits a real part or drawing on a real
//! machine; each keeps a careless or hostile input from running for minutes, exhausting memory
//! or overflowing the stack (issue 42's cases: a coordinate of 1e308, 100,000 nested SVG groups,
//! a tool of diameter 1e9, a step-down of 1e-9).

/// The largest part, drawing, stock or length a job may hold (mm): 10 m, more than any machine
/// swarf writes for travels. A file whose extent passes it holds a coordinate out of range (or
/// is in the wrong unit), and is refused with its size and the element that makes it.
pub const MAX_SIZE: f64 = 10_000.0;

/// The largest file swarf reads (bytes): 512 MiB, a binary STL of over ten million facets.
/// A bigger one (or a device that never ends, `/dev/zero`) is refused saying so.
pub const MAX_FILE_BYTES: u64 = 512 << 20;

/// The farthest a part's coordinate may lie from its file's origin, in the file's own unit:
/// 10 km in millimetres, so a part drawn in microns, or far from its origin, still reads; a
/// coordinate beyond it is a damaged number (1e39, 1e308), refused with its triangle.
pub const MAX_COORDINATE: f64 = 1e7;

/// The largest tool diameter (mm): a face mill of a metre is already beyond any spindle.
pub const MAX_TOOL_DIAMETER: f64 = 1_000.0;

/// The smallest tool diameter (mm): below a hundredth of a millimetre no cutter exists, and
/// a z-map fine enough for it would not fit in memory.
pub const MIN_TOOL_DIAMETER: f64 = 0.01;

/// The deepest nesting of elements in an SVG (groups in groups): Inkscape's deepest real files
/// nest a few dozen; deeper is refused before the walk would overflow the stack.
pub const MAX_NESTING: usize = 256;

/// The most operations a job may hold.
pub const MAX_OPERATIONS: usize = 100;

/// The most setups a job holds: a block has six faces, and a part turned in the vise a few
/// more ways.
pub const MAX_SETUPS: usize = 12;
/// Tabs on one loop of a profile: more than any part is held by (a tab every 4 mm round a
/// 1 m × 1 m sheet is 1,000).
pub const MAX_TABS: u32 = 1_000;

/// The most tools a job's library may hold.
pub const MAX_TOOLS: usize = 1_000;

/// The most pieces (lines and arcs) a drawing may hold once its curves are fitted.
pub const MAX_PIECES: usize = 2_000_000;

/// The highest degree of a DXF SPLINE (AutoCAD draws up to 11).
pub const MAX_SPLINE_DEGREE: usize = 25;

/// The most levels (step-downs) one operation may cut.
pub const MAX_LEVELS: f64 = 2000.0;

/// The most passes (raster lines, rings) one operation may cut at a level.
pub const MAX_PASSES: f64 = 20000.0;

/// The most turns one helix may make (a helical entry, a bore, a thread): a bore of 50 mm at
/// a 0.025 mm pitch. More is a pitch or helix radius in the wrong unit (1e-9), whose moves
/// would not fit in memory.
pub const MAX_TURNS: f64 = 2000.0;

/// The most pecks a drilling cycle may make in one hole: a 100 mm hole at a 0.05 mm peck. A
/// peck of 1e-9 mm would make billions of moves to simulate.
pub const MAX_PECKS: f64 = 2000.0;

/// The most points at which zigzag roughing weighs the load on its passes, over all levels
/// (the stock's area over the step-over and sampling, a level at a time): 4 million take a few
/// seconds; a sampling of 0.001 mm, or a φ0.01 tool, asks hundreds of millions.
pub const MAX_LOAD_SAMPLES: f64 = 4_000_000.0;

/// The most rows of its levels' maps zigzag roughing sweeps to weigh the load at a sampling
/// or pixel finer than its defaults (each point weighed sweeps the tool's disk, its diameter
/// over the pixel in rows): 15 million take about 6 s on the 90 mm sample; a sampling of 0.05
/// mm there swept 45 million and ran for minutes, though its 0.8 million points were few.
pub const MAX_LOAD_ROWS: f64 = 15_000_000.0;

/// The most nodes of a CL z-map (or cells of a simulation): 50 million f64 heights are 400 MB,
/// what a browser tab can hold beside the rest of the job.
pub const MAX_NODES: usize = 50_000_000;

/// The most level-map nodes a level-by-level operation (roughing, waterline) reads, over all
/// its levels (levels × the nodes of its grid over the stock): each level's region is found
/// over the whole map, 0.06–0.1 s a million (release build: 72 million for the 200 mm
/// wheel_in_box at a 0.5 mm step-down took 4.4 s, 149 million for a waterline at 0.02 mm on
/// the 90 mm sample 10.9 s of its 18). 150 million are wheel_in_box's waterline at a 0.25 mm
/// step-down on the default 0.25 mm grid; a step-down of 0.015 mm on the sample asks 198
/// million, and a grid of 0.04 mm there 233 million at a 0.5 mm step-down.
pub const MAX_LEVEL_NODES: f64 = 150_000_000.0;

/// The most cut one clearing of a level-by-level roughing may plan (mm): the area of its
/// levels' regions over the step-over, known before any ring is made. Planning and
/// simulating take 20–30 µs a mm of it (release build): 0.65 km for the 200 mm wheel_in_box
/// at a 0.5 mm step-down with a φ10 took 13.7 s, 0.49 km for the 90 mm sample at 0.1 mm
/// with its φ6 13.2 s, and 0.99 km there at 0.05 mm 28 s. 0.75 km is 12 hours of cutting at
/// 1 m/min.
pub const MAX_CUT_LENGTH: f64 = 750_000.0;

/// The most rings one clearing of a level-by-level roughing may plan, over all its levels'
/// regions (each region's inradius over the step-over), each an offset of its region however
/// close to the last: a step-over of 0.06 mm on the sample (about 7,600) took 9 s, one of
/// 0.006 mm on the 40 mm warm-up part (16,000) 20 s.
pub const MAX_RINGS: f64 = 5_000.0;

/// The most points a surface-following path (raster finishing) may have before it is reduced:
/// step-over and grid over the stock's area. 10 million are a 200 mm mould at a 0.1 mm
/// step-over and a 0.04 mm grid; the Khronos Duck read as the 1.7 m its glTF says, finished
/// at the default step-over and grid, is 13 million (and 10 GB).
pub const MAX_PATH_POINTS: f64 = 10_000_000.0;

/// The fastest feed or rapid rate (mm/min): 1,000 m/min is beyond any machine tool.
pub const MAX_FEED: f64 = 1_000_000.0;

/// The fastest spindle (rpm).
pub const MAX_RPM: f64 = 1_000_000.0;

/// The longest a tool change may take (s): a day.
pub const MAX_TOOL_CHANGE: f64 = 86_400.0;

/// The range of each of the job's tolerances (mm; the normal's and area's are ratios and mm²):
/// below its least the work grows without bound (an interpolation tolerance of 1e-9 asks for
/// billions of points), above its most the result is no longer a tolerance of anything (a
/// gouge tolerance of 10 mm passed a program cutting 9 mm into the part: past half a millimetre
/// no finished part is within it).
pub const TOLERANCE_RANGES: [(&str, f64, f64); 10] = [
    ("degenerateArea", 0.0, 1.0),
    ("chordal", 1e-5, 1.0),
    ("height", 1e-12, 0.01),
    ("interpolation", 1e-5, 0.1),
    ("normal", 0.0, 1e-3),
    ("gouge", 1e-4, 0.5),
    ("chain", 1e-6, 1.0),
    ("arcFit", 1e-5, 1.0),
    ("microEntity", 0.0, 0.1),
    ("offset", 1e-12, 1e-3),
];

/// Whether `v` is a length a job may give (finite, at most [`MAX_SIZE`] either way).
pub fn in_size(v: f64) -> bool {
    v.is_finite() && v.abs() <= MAX_SIZE
}

/// A number as a message shows it: plainly, or in exponent form where plain would run to dozens
/// of digits (a coordinate of 1e308 is not 309 digits long on the screen).
pub fn shown(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-6..1e9).contains(&v.abs()) {
        // Four significant digits, without trailing zeros: 3.266e17, 1e308, 1e-9.
        let text = format!("{v:.3e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
        format!("{mantissa}e{exponent}")
    } else {
        format!("{v}")
    }
}

/// The most cutting edges a tool may have.
pub const MAX_FLUTES: u32 = 16;
