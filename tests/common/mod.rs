//! Parts with known answers, made by the tests themselves.
#![allow(dead_code)]

use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::mesh::Mesh;

pub fn mesh(tris: Vec<[DVec3; 3]>) -> Mesh {
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap()
}

/// The plane z = z0 + gx x + gy y over [-half, half]², as two triangles.
pub fn plane(half: f64, z0: f64, gx: f64, gy: f64) -> Mesh {
    let p = |x: f64, y: f64| DVec3::new(x, y, z0 + gx * x + gy * y);
    let (a, b, c, d) = (p(-half, -half), p(half, -half), p(half, half), p(-half, half));
    mesh(vec![[a, b, c], [a, c, d]])
}

/// A step: z = 0 for x < 0 and z = h for x >= 0, over [-half, half]², with the vertical wall.
pub fn step(half: f64, h: f64) -> Mesh {
    let v = DVec3::new;
    mesh(vec![
        [v(-half, -half, 0.0), v(0.0, -half, 0.0), v(0.0, half, 0.0)],
        [v(-half, -half, 0.0), v(0.0, half, 0.0), v(-half, half, 0.0)],
        [v(0.0, -half, 0.0), v(0.0, -half, h), v(0.0, half, h)],
        [v(0.0, -half, 0.0), v(0.0, half, h), v(0.0, half, 0.0)],
        [v(0.0, -half, h), v(half, -half, h), v(half, half, h)],
        [v(0.0, -half, h), v(half, half, h), v(0.0, half, h)],
    ])
}

/// A roof: z = h - s |x| over [-half, half]², its sharp ridge along the Y axis.
pub fn roof(half: f64, h: f64, s: f64) -> Mesh {
    let v = |x: f64, y: f64| DVec3::new(x, y, h - s * x.abs());
    mesh(vec![
        [v(-half, -half), v(0.0, -half), v(0.0, half)],
        [v(-half, -half), v(0.0, half), v(-half, half)],
        [v(0.0, -half), v(half, -half), v(half, half)],
        [v(0.0, -half), v(half, half), v(0.0, half)],
    ])
}

/// The upper half of a sphere of radius `r` about the origin, tessellated as a height field on
/// an xy grid of `spacing` with every vertex on the sphere (so the mesh lies inside it), up to
/// the radius `rim` where the surface is still far from vertical.
pub fn cap(r: f64, rim: f64, spacing: f64) -> Mesh {
    let n = (2.0 * rim / spacing).ceil() as i64;
    let at = |i: i64, j: i64| {
        let (x, y) = (-rim + i as f64 * spacing, -rim + j as f64 * spacing);
        DVec3::new(x, y, (r * r - x * x - y * y).max(0.0).sqrt())
    };
    let inside = |p: DVec3| p.truncate().length() <= rim;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if [a, b, c, d].iter().all(|&p| inside(p)) {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
    }
    mesh(tris)
}

/// Largest sag of a chord of length `chord` below a sphere of radius `r`.
pub fn sag(r: f64, chord: f64) -> f64 {
    r - (r * r - chord * chord / 4.0).sqrt()
}

/// Exact tip height of a cutter (radius `cr`, corner `a`) over a sphere of radius `rs` about the
/// origin, standing at `c`.
pub fn over_sphere(rs: f64, cr: f64, a: f64, c: DVec2) -> f64 {
    let off = (c.length() - (cr - a)).max(0.0);
    ((rs + a).powi(2) - off * off).sqrt() - a
}

/// Where the repository's shared data lives, if it is beside the checkout.
pub fn shared_data(rel: &str) -> Option<std::path::PathBuf> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data").join(rel);
    if p.exists() {
        Some(p)
    } else {
        eprintln!("skipping: {} is absent (shared data is not beside this checkout)", p.display());
        None
    }
}

/// LinuxCNC's interpreter (`rs274 -g`) on a program with `tools` in its tool table: its
/// canonical calls, one a line. Panics where it refuses the program.
pub fn rs274(gcode: &str, tools: &[swarf::job::Tool]) -> String {
    use std::sync::atomic::{AtomicU64, Ordering};
    static RUN: AtomicU64 = AtomicU64::new(0);
    let dir = std::env::temp_dir().join(format!("swarf-rs274-{}-{}", std::process::id(), RUN.fetch_add(1, Ordering::Relaxed)));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("program.ngc");
    std::fs::write(&program, gcode).unwrap();
    let table = dir.join("tool.tbl");
    let lines: String = tools.iter().map(|t| format!("T{0} P{0} Z0.000 D{1:.3} ;{2}\n", t.number, t.cutter.diameter, t.describe())).collect();
    std::fs::write(&table, lines).unwrap();
    // rs274 keeps its parameter file in the working directory and its tool table in a file
    // mapped from $HOME (~/.tool.mmap): each run gets its own, so parallel tests cannot mix
    // their tool tables.
    let output = match std::process::Command::new("rs274").current_dir(&dir).env("HOME", &dir).arg("-g").arg("-t").arg(&table).arg(&program).output() {
        Ok(o) => o,
        Err(e) => panic!("rs274 (LinuxCNC's interpreter) could not be run: {e}; scripts/setup.sh installs it (apt-get install linuxcnc-uspace)"),
    };
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let tail: Vec<&str> = stdout.lines().rev().take(8).collect();
    assert!(output.status.success() && !stderr.contains("rror"), "rs274 refused the program:\n{stderr}\n{}", tail.join("\n"));
    let _ = std::fs::remove_dir_all(&dir);
    stdout
}

/// GRBL 1.1h's own parser (`../shared/tools/grbl/grblcheck`, built from GRBL's source on first
/// use) on a program: `None` where the shared tools are not beside this checkout, else what the
/// parser said (`Err` with its message when it refused a line).
pub fn grblcheck(gcode: &str) -> Option<Result<(), String>> {
    let tool = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/tools/grbl/grblcheck");
    if !tool.exists() {
        eprintln!("skipping GRBL's own parser: {} is absent", tool.display());
        return None;
    }
    let dir = std::env::temp_dir().join(format!("swarf-grblcheck-{}-{:?}", std::process::id(), std::thread::current().id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("program.nc");
    std::fs::write(&file, gcode).unwrap();
    // One at a time over every process (`flock`): the first call builds the validator into a
    // folder it empties first, and two first calls at once (two tests of one binary on a fresh
    // machine) emptied each other's build.
    let lock = std::env::temp_dir().join("swarf-grblcheck.lock");
    let out = std::process::Command::new("flock").arg(&lock).arg("bash").arg(&tool).arg(&file).output().expect("flock runs grblcheck");
    let _ = std::fs::remove_dir_all(&dir);
    let said = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!said.contains("could not build"), "{said}");
    Some(if out.status.success() && said.contains("grblcheck: OK") { Ok(()) } else { Err(said) })
}

/// OpenCAMLib's drop cutter on a program (`../shared/tools/gcheck.py`, run by the project's
/// `.venv`, where scripts/setup.sh installs OpenCAMLib) against `part` in the program's
/// coordinates, with `tools` (flat, ball and bull-nose ends) as its tool table: what it said,
/// its last line `gcheck: OK …` or `gcheck: FAIL …`; `None` where the shared tools or
/// OpenCAMLib are absent.
pub fn gcheck(gcode: &str, part: &Mesh, tools: &[swarf::job::Tool]) -> Option<String> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let (script, python) = (root.join("../shared/tools/gcheck.py"), root.join(".venv/bin/python"));
    let has_ocl = || std::process::Command::new(&python).args(["-c", "import opencamlib"]).output().is_ok_and(|o| o.status.success());
    if !script.exists() || !has_ocl() {
        eprintln!("skipping OpenCAMLib's drop cutter: {} or OpenCAMLib in {} is absent (scripts/setup.sh installs it)", script.display(), python.display());
        return None;
    }
    use std::sync::atomic::{AtomicU64, Ordering};
    static RUN: AtomicU64 = AtomicU64::new(0);
    let dir = std::env::temp_dir().join(format!("swarf-gcheck-{}-{}", std::process::id(), RUN.fetch_add(1, Ordering::Relaxed)));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("program.ngc"), gcode).unwrap();
    std::fs::write(dir.join("part.stl"), part.to_binary_stl()).unwrap();
    let mut command = std::process::Command::new(&python);
    command.current_dir(&dir).env("HOME", &dir).arg(&script).arg("program.ngc").args(["--mesh", "part.stl"]);
    for t in tools {
        use swarf::cutter::Shape;
        let kind = match t.cutter.shape {
            Shape::Ball => format!("ball:{}", t.cutter.diameter),
            Shape::BullNose => format!("bull:{}:{}", t.cutter.diameter, t.cutter.corner_radius),
            _ => format!("flat:{}", t.cutter.diameter),
        };
        command.args(["--tool", &kind, "--tool-number", &t.number.to_string()]);
    }
    let out = command.output().expect("python runs gcheck.py");
    let _ = std::fs::remove_dir_all(&dir);
    Some(format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr)))
}

/// Judges tool paths against the brute-force exact drop ([`cl_exact_at`] over every facet, edge
/// and vertex within the cutter's reach of a move), at dense points along every feed move.
pub struct Judge<'a> {
    pub part: &'a Mesh,
    pub profile: swarf::cutter::Profile,
    /// Where no part is under the cutter.
    pub floor: f64,
}

/// The deepest a path goes below the exact surface, and where.
#[derive(Clone, Copy, Debug)]
pub struct Deepest {
    pub depth: f64,
    pub at: DVec3,
    pub points: usize,
}

impl Judge<'_> {
    /// The triangles within reach of the box `[lo, hi]`, as a mesh (or `None`).
    fn near(&self, lo: DVec2, hi: DVec2) -> Option<Mesh> {
        let r = self.profile.radius + 1e-6;
        let tris: Vec<[DVec3; 3]> = self
            .part
            .triangles()
            .filter(|t| {
                let b = t.bounds();
                b.min.x <= hi.x + r && b.max.x >= lo.x - r && b.min.y <= hi.y + r && b.max.y >= lo.y - r
            })
            .map(|t| [t.a, t.b, t.c])
            .collect();
        (!tris.is_empty()).then(|| Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap())
    }

    /// The exact tip height over `c` (the floor where nothing is in reach).
    pub fn exact(&self, c: DVec2) -> f64 {
        self.near(c, c).and_then(|m| swarf::zmap::cl_exact::cl_exact_at(&m, &self.profile, c, &Tolerances::DEFAULT)).unwrap_or(self.floor).max(self.floor)
    }

    /// The deepest point of the feed moves below the exact surface plus `allowance`, sampled at
    /// `per_mm` points a millimetre (and both ends of every move).
    pub fn deepest(&self, start: DVec3, moves: &[swarf::toolpath::Move], allowance: f64, per_mm: f64) -> Deepest {
        let mut worst = Deepest { depth: f64::NEG_INFINITY, at: start, points: 0 };
        let mut at = start;
        for m in moves {
            let to = m.to();
            if let swarf::toolpath::Move::Line { .. } = m {
                let (lo, hi) = (at.truncate().min(to.truncate()), at.truncate().max(to.truncate()));
                let near = self.near(lo, hi);
                let n = ((at.truncate().distance(to.truncate()) * per_mm).ceil() as usize).max(1);
                for k in 0..=n {
                    let p = at.lerp(to, k as f64 / n as f64);
                    let exact = near.as_ref().and_then(|m| swarf::zmap::cl_exact::cl_exact_at(m, &self.profile, p.truncate(), &Tolerances::DEFAULT)).unwrap_or(self.floor).max(self.floor);
                    let depth = exact + allowance - p.z;
                    worst.points += 1;
                    if depth > worst.depth {
                        worst.depth = depth;
                        worst.at = p;
                    }
                }
            }
            at = to;
        }
        worst
    }
}

/// A terrain of flat facets within about 7° of horizontal, its heights on a lattice quantised so
/// that many edges are exactly horizontal and many neighbouring facets are mirror images: ridges
/// and valleys along the grid, across it and diagonal. `shift` moves the lattice against the
/// z-map grid (0: ridges through the nodes).
pub fn faceted_terrain(seed: u64, lattice: f64, shift: f64) -> Mesh {
    let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 33) as f64 / (1u64 << 31) as f64
    };
    let n = 12;
    // Quantised heights: steps of lattice × 0.06 keep every slope under about 7°.
    let heights: Vec<f64> = (0..(n + 1) * (n + 1)).map(|_| (next() * 3.0).floor() * lattice * 0.06).collect();
    let min = DVec2::splat(-(n as f64) * lattice / 2.0 + shift);
    let top = |x: f64, y: f64| {
        let i = ((x - min.x) / lattice).round() as usize;
        let j = ((y - min.y) / lattice).round() as usize;
        heights[j.min(n) * (n + 1) + i.min(n)]
    };
    swarf::mesh::sample::height_field_solid(min, min + DVec2::splat(n as f64 * lattice), n, n, -3.0, top)
}

/// A small random number generator for generated parts (a linear congruential one: the same
/// seed makes the same part on every machine).
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A relief of sharp peaks and knees: heights drawn at random on a lattice whose spacing does
/// not divide the z-map's, so its ridges, knees and peaks fall between the nodes.
pub fn spiky_terrain(seed: u64, half: f64, lattice: f64, amplitude: f64) -> Mesh {
    let mut rng = Lcg(seed);
    let n = (2.0 * half / lattice).round() as usize;
    let heights: Vec<f64> = (0..(n + 1) * (n + 1)).map(|_| amplitude * rng.next().powi(3)).collect();
    let min = DVec2::splat(-half);
    let step = 2.0 * half / n as f64;
    let top = |x: f64, y: f64| {
        let i = ((x - min.x) / step).round() as usize;
        let j = ((y - min.y) / step).round() as usize;
        heights[j.min(n) * (n + 1) + i.min(n)]
    };
    swarf::mesh::sample::height_field_solid(min, DVec2::splat(half), n, n, -4.0, top)
}

/// A mesa: a flat top at `h` over |x| < `w` with 60° flanks, its knees (the flanks' top and foot
/// edges) at x = ±w, ±(w + h / tan 60°): place them between nodes by the choice of `w`.
pub fn mesa(w: f64, h: f64, half: f64) -> Mesh {
    let run = h / 3f64.sqrt();
    let xs = [-half, -w - run, -w, w, w + run, half];
    let zs = [0.0, 0.0, h, h, 0.0, 0.0];
    let mut tris = Vec::new();
    for k in 0..xs.len() - 1 {
        let (a, b) = (DVec3::new(xs[k], -half, zs[k]), DVec3::new(xs[k + 1], -half, zs[k + 1]));
        let (c, d) = (DVec3::new(xs[k + 1], half, zs[k + 1]), DVec3::new(xs[k], half, zs[k]));
        tris.push([a, b, c]);
        tris.push([a, c, d]);
    }
    mesh(tris)
}

/// Checks a verified program: a clean report (no gouge, no rapid through stock, no tool body
/// in material), and no vertical feed into material but a drill's. A start counts as in the air when the
/// stock there stands no more than the gouge tolerance (0.02 mm) above the cutter: up to that
/// skin over its footprint.
pub fn clean(out: &swarf::job::JobOutput) {
    let v = out.verification.as_ref().expect("verified");
    assert!(v.report.is_clean(), "{}", v.report.describe());
    for (m, &vol) in out.moves.iter().zip(&v.volumes) {
        if let swarf::toolpath::Move::Line { to, .. } = m.mv {
            let drill = matches!(m.cutter.shape, swarf::cutter::Shape::Drill | swarf::cutter::Shape::SpotDrill);
            if !drill && to.truncate().distance(m.from.truncate()) < 1e-9 && to.z < m.from.z - 1e-9 {
                let r = m.cutter.diameter / 2.0;
                assert!(vol < 0.02 * std::f64::consts::PI * r * r + 1e-6, "a straight plunge to {to} removed {vol} mm³");
            }
        }
    }
}

/// Every cell of a simulated stock: its place, whether `shape` holds it, its distance from the
/// shape's boundary, and the stock's top there (for judging a 2.5D cut against its drawing).
pub fn cells<'a>(stock: &'a swarf::sim::dexel::DexelStock, shape: &'a swarf::drawing::Shape) -> impl Iterator<Item = (DVec2, bool, f64, f64)> + 'a {
    let grid = stock.grid();
    (0..grid.ny).flat_map(move |j| (0..grid.nx).map(move |i| (i, j))).map(move |(i, j)| {
        let p = grid.node(i, j);
        (p, shape.contains(p), shape.distance_to(p), stock.top(i, j))
    })
}

/// The CPU time this thread has used, in seconds (`CLOCK_THREAD_CPUTIME_ID`): what a test bounds
/// a job's work by, where a wall clock would time the machine's other load as well.
#[cfg(unix)]
pub fn thread_cpu_seconds() -> f64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the one timespec it is given.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "this thread's CPU clock");
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// `f`'s answer and the CPU seconds its work took, all of it on this thread
/// ([`swarf::parallel::alone`], as the page's engine runs it), so the figure is the whole work
/// and nothing of the tests or programs running beside it: it does not grow on a busy machine.
#[cfg(unix)]
pub fn cpu_timed<R>(f: impl FnOnce() -> R) -> (R, f64) {
    swarf::parallel::alone(|| {
        let start = thread_cpu_seconds();
        let out = f();
        (out, thread_cpu_seconds() - start)
    })
}
