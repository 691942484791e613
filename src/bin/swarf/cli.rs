//! The commands, their arguments and what they print.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand, ValueEnum};
use swarf::cutter::{Cutter, Shape};
use swarf::drawing::import::read_drawing;
use swarf::geom::Tolerances;
use swarf::job::project::Project;
use swarf::job::verify_gcode;
use swarf::job::Workpiece;
use swarf::job::{self, Job};
use swarf::mesh::import::read_mesh_auto;
use swarf::mesh::placement::{PartSetup, PartUnits, Placement, UpAxis};
use swarf::mesh::sample::{demo_part, two_sided_part};
use swarf::progress::Progress;
use swarf::zmap::{cc::cc_zmap, cl_exact::cl_exact, cl_inverse::cl_inverse_offset, io, Grid};

#[derive(Parser)]
#[command(name = "swarf", version, about = "CAM: parts in, gouge-free tool paths and G-code out")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a job file on a part, or a project file (`.swarf.json`, the part inside or beside
    /// it), and write G-code.
    Run {
        /// Job (JSON), as saved by the page or printed by `swarf job`; or a project.
        job: PathBuf,
        /// The part (STL, glTF/GLB, OBJ) or drawing (DXF, SVG); for a project, instead of its own.
        part: Option<PathBuf>,
        /// Where to write the G-code (default: the part's or project's name with the extension
        /// the post names: .ngc, .nc, .tap).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Print no progress.
        #[arg(short, long)]
        quiet: bool,
        /// Write the program even when its simulation finds a gouge, a rapid move through stock
        /// or the tool's body in material (it then starts with a warning comment). Without it
        /// such a program is not written and the command fails.
        #[arg(long)]
        write_anyway: bool,
        /// After the program, print how long each stage of the job took, in the order they
        /// ran (where planning spends its time; BENCHMARKS.md's profiles).
        #[arg(long)]
        stage_times: bool,
    },
    /// Make a project file (`.swarf.json`) of a job and its part or drawing, to open in the
    /// page or run with `swarf run`.
    Project {
        /// Job (JSON).
        job: PathBuf,
        /// The part or drawing.
        part: PathBuf,
        /// Where to write the project (default: the part's name with .swarf.json).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Name the part instead of embedding it (it must then stay beside the project).
        #[arg(long)]
        reference: bool,
    },
    /// Make the built-in sample part, its job and its G-code in a folder.
    Demo {
        /// Folder to write demo.stl, demo.json and demo.ngc into.
        #[arg(short, long, default_value = ".")]
        output: PathBuf,
        /// The two-sided example instead: a plate with a pocket on top and a slot and a boss
        /// underneath, machined in two setups (two-sided.stl, two-sided.json and one program a
        /// setup).
        #[arg(long)]
        two_sided: bool,
    },
    /// Write a job's setup sheet for a part (printable HTML): for each setup how to hold the
    /// part, its work offset and zero, the stock, a picture from above, the tools, the
    /// operations and the cycle times.
    Sheet {
        /// Job (JSON), with setups or without (one setup).
        job: PathBuf,
        /// The part (STL, glTF/GLB, OBJ).
        part: PathBuf,
        /// Where to write the sheet (default: the part's name with .sheet.html).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Read a tool library machinists keep (Fusion's JSON, a LinuxCNC .tbl, FreeCAD .fctb bits
    /// or a .fctl library with its bits) and print it as swarf's tools (JSON, for a job's
    /// `tools`), or as another library (`--to`); what it holds that swarf does not take is said
    /// on stderr.
    Tools {
        /// The library, then for a FreeCAD .fctl the bit files it names.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// A LinuxCNC tool table is in inches (it does not say).
        #[arg(long)]
        inches: bool,
        /// Print it as `fusion` (Fusion's tool library JSON) or `linuxcnc` (a tool table), or
        /// write it as `freecad` (a `.fctl` library and a `.fctb` bit a tool) into `--out`.
        #[arg(long)]
        to: Option<String>,
        /// The folder a FreeCAD library is written into (`--to freecad`); its name is the
        /// folder's.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Print the default job as JSON, to edit and pass to `swarf run`.
    Job {
        /// The default job for a drawing (DXF, SVG): a profile around its loops.
        #[arg(long)]
        drawing: bool,
    },
    /// List what a drawing (DXF, SVG) holds: layers, loops (index, layer, outside or hole,
    /// size) and open chains, to choose what operations cut.
    Drawing { file: PathBuf },
    /// List the holes a drilling operation finds: a part's vertical round holes (centre,
    /// diameter, top and bottom, through or blind with a flat or cone bottom) or a drawing's
    /// circles, placed as the job places the part, numbered as a drilling operation's `holes`
    /// takes them, and grouped by diameter.
    Holes {
        /// The part (STL, glTF/GLB, OBJ) or drawing (DXF, SVG).
        file: PathBuf,
        /// The job whose placement to use (default: the default job's).
        #[arg(long)]
        job: Option<PathBuf>,
        /// A part's round bosses instead (studs for an external thread: threadMill with
        /// external), numbered as the thread mill's `holes` takes them.
        #[arg(long)]
        bosses: bool,
    },
    /// List a part's top edges as a chamfer (edges: partEdges) finds them: the outlines of its
    /// horizontal faces, numbered as the chamfer's `loops` takes them, each sharp (dropping down
    /// a steep wall all round: a chamfer can break it) or not, placed as the job places the part.
    Edges {
        /// The part (STL, glTF/GLB, OBJ).
        file: PathBuf,
        /// The job whose placement to use (default: the default job's).
        #[arg(long)]
        job: Option<PathBuf>,
    },
    /// Simulate a G-code program on a job's stock and check it against the part: gouges, rapid
    /// moves through stock, the tool's body in material, material left. Exits with 1 when it
    /// finds a problem.
    Verify {
        /// Job (JSON): the part's placement, the stock, the tools and the allowance.
        job: PathBuf,
        /// The part: STL, glTF/GLB or OBJ.
        part: PathBuf,
        /// The program (G-code).
        program: PathBuf,
        /// Cell size of the simulated stock (mm); default: the job's.
        #[arg(long)]
        cell: Option<f64>,
        /// Print the report as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Write the CL z-map of a cutter over a part, for comparing heights point by point.
    Zmap {
        part: PathBuf,
        #[arg(long, value_enum, default_value_t = ShapeArg::Ball)]
        shape: ShapeArg,
        /// Cutter diameter (mm).
        #[arg(long, default_value_t = 6.0)]
        diameter: f64,
        /// Corner radius of a bull nose (mm).
        #[arg(long, default_value_t = 1.0)]
        corner: f64,
        /// Included angle of a V-bit (degrees).
        #[arg(long, default_value_t = 90.0)]
        angle: f64,
        /// Tip diameter of a V-bit (mm; 0 for a point).
        #[arg(long, default_value_t = 0.0)]
        tip: f64,
        /// Grid spacing (mm).
        #[arg(long, default_value_t = 0.5)]
        grid: f64,
        #[arg(long, value_enum, default_value_t = BuilderArg::Exact)]
        builder: BuilderArg,
        /// The part's units.
        #[arg(long, value_enum, default_value_t = UnitsArg::Auto)]
        units: UnitsArg,
        /// The part's up axis is Y.
        #[arg(long)]
        y_up: bool,
        /// Centre the part and put its top at z = 0 (default: keep the file's coordinates).
        #[arg(long)]
        center_top: bool,
        /// Height of nodes the cutter cannot reach the part from (default: the part's bottom).
        #[arg(long, allow_negative_numbers = true)]
        floor: Option<f64>,
        #[arg(long, value_enum, default_value_t = FormatArg::Csv)]
        format: FormatArg,
        #[arg(short, long)]
        output: PathBuf,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum ShapeArg {
    Flat,
    Ball,
    BullNose,
    VBit,
}
#[derive(Clone, Copy, ValueEnum)]
enum BuilderArg {
    Exact,
    Inverse,
}
#[derive(Clone, Copy, ValueEnum)]
enum UnitsArg {
    /// As the format says: metres for glTF, mm for STL and OBJ.
    Auto,
    Mm,
    Inch,
    M,
}
#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
    Csv,
    Raw,
}

pub fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("swarf: {message}");
            ExitCode::FAILURE
        }
    }
}

/// The job file's job, or the default job.
fn job_or_default(path: Option<&Path>) -> Result<Job, String> {
    match path {
        Some(path) => read_job(path),
        None => Ok(Job::default()),
    }
}

/// A part file read as a mesh with the job's tolerances.
fn read_part(file: &Path, job: &Job) -> Result<swarf::mesh::Mesh, String> {
    let name = file.file_name().map(|n| n.to_string_lossy().into_owned());
    read_mesh_auto(&read(file)?, name.as_deref(), &job.tolerances).map_err(|e| format!("{}: {e}", file.display()))
}

fn read(path: &Path) -> Result<Vec<u8>, String> {
    bounded(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// A file's bytes, at most [`swarf::limits::MAX_FILE_BYTES`] of them: a bigger file (or a
/// device without end) is refused saying the limit, before more than that is read.
fn bounded(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let limit = swarf::limits::MAX_FILE_BYTES;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::other(format!("it is larger than {} MiB, the most swarf reads", limit >> 20)));
    }
    Ok(bytes)
}

/// Refuses an output that is one of the command's inputs (`-o part.stl` would put G-code in
/// place of the part): compared as the files they are, whatever the path's spelling.
fn not_an_input(output: &Path, inputs: &[&Path]) -> Result<(), String> {
    let Ok(out) = std::fs::canonicalize(output) else { return Ok(()) };
    for input in inputs {
        if std::fs::canonicalize(input).is_ok_and(|i| i == out) {
            return Err(format!("{} is an input of this command: name another file to write (-o), it would be overwritten", output.display()));
        }
    }
    Ok(())
}

/// A job file read, with a mesh stock it only names read from beside it.
fn read_job(path: &Path) -> Result<Job, String> {
    let job = Job::from_json(&String::from_utf8_lossy(&read(path)?)).map_err(|e| e.to_string())?;
    embed_beside(job, path)
}

/// `job` (read from `file`) with the mesh stock it names (`stock.mesh.name`, without its
/// bytes) read from beside `file` and carried in it.
fn embed_beside(mut job: Job, file: &Path) -> Result<Job, String> {
    if let Some(mesh) = job.stock.mesh.as_mut().filter(|m| m.data.is_none() && m.given.is_none()) {
        let path = file.parent().map(Path::to_path_buf).unwrap_or_default().join(&mesh.name);
        let bytes = bounded(&path).map_err(|e| format!("{}: stock.mesh names {}, which cannot be read: {e}", file.display(), path.display()))?;
        *mesh = swarf::job::blank::MeshFile::embedded(&mesh.name, &bytes);
    }
    Ok(job)
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    std::fs::write(path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Run { job: file, part, output, quiet, write_anyway, stage_times } => {
            let text = String::from_utf8_lossy(&read(&file)?).into_owned();
            // The part a project names beside it is an input too.
            let mut named = None;
            let (job, name, bytes, stem) = if Project::is_project(&text) {
                let project = Project::from_json(&text).map_err(|e| format!("{}: {e}", file.display()))?;
                let (name, bytes) = match &part {
                    Some(part) => (part.file_name().map(|n| n.to_string_lossy().into_owned()), read(part)?),
                    None => {
                        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
                        named = Some(dir.join(&project.workpiece.name));
                        (Some(project.workpiece.name.clone()), project.workpiece_bytes(|n| bounded(&dir.join(n))).map_err(|e| format!("{}: {e}", file.display()))?)
                    }
                };
                let stem = file.to_string_lossy().trim_end_matches(".json").trim_end_matches(".swarf").to_owned();
                (embed_beside(project.job, &file)?, name, bytes, PathBuf::from(stem))
            } else {
                let job = embed_beside(Job::from_json(&text).map_err(|e| e.to_string())?, &file)?;
                let Some(part) = part.as_deref() else { return Err(format!("{}: a job file needs a part: swarf run job.json part.stl", file.display())) };
                (job, part.file_name().map(|n| n.to_string_lossy().into_owned()), read(part)?, part.with_extension(""))
            };
            let workpiece = Workpiece::read(&bytes, name.as_deref(), &job.tolerances).map_err(|e| e.to_string())?;
            let output = output.unwrap_or_else(|| stem.with_extension(job.post.extension()));
            // The default name too: a part named part.ngc would become its own program.
            not_an_input(&output, &[&file, part.as_deref().unwrap_or(&file), named.as_deref().unwrap_or(&file)])?;
            run_job(&job, workpiece, &output, RunOptions { quiet, write_anyway, stage_times })
        }
        Command::Project { job: job_file, part, output, reference } => {
            let job = read_job(&job_file)?;
            let name = part.file_name().map(|n| n.to_string_lossy().into_owned()).ok_or_else(|| format!("{}: not a file", part.display()))?;
            let project = if reference { Project::referencing(job, &name) } else { Project::embedded(job, &name, &read(&part)?) };
            let output = output.unwrap_or_else(|| part.with_extension("swarf.json"));
            not_an_input(&output, &[&job_file, &part])?;
            write(&output, project.to_json().as_bytes())?;
            println!("wrote {}", output.display());
            Ok(())
        }
        Command::Demo { output, two_sided } => {
            std::fs::create_dir_all(&output).map_err(|e| format!("cannot create {}: {e}", output.display()))?;
            let (name, job, part) = if two_sided { ("two-sided", Job::two_sided(), two_sided_part()) } else { ("demo", Job::demo(), demo_part()) };
            let stl = part.to_binary_stl();
            write(&output.join(format!("{name}.stl")), &stl)?;
            write(&output.join(format!("{name}.json")), serde_json::to_string_pretty(&job).unwrap().as_bytes())?;
            // The program is made from the STL as written (f32), so that `swarf run demo.json
            // demo.stl` gives the same program.
            let part = read_mesh_auto(&stl, Some("part.stl"), &job.tolerances).map_err(|e| e.to_string())?;
            run_job(&job, part, &output.join(format!("{name}.{}", job.post.extension())), RunOptions { quiet: false, write_anyway: false, stage_times: false })
        }
        Command::Sheet { job: job_file, part, output } => {
            let job = read_job(&job_file)?;
            let mesh = read_part(&part, &job)?;
            let output = output.unwrap_or_else(|| part.with_extension("sheet.html"));
            not_an_input(&output, &[&job_file, &part])?;
            let setups = job::run_setups(&job, mesh, &mut Progress::none()).map_err(|e| e.to_string())?;
            let name = part.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            write(&output, job::sheet::setup_sheet(&job, &name, &setups.iter().map(|s| job::sheet::SheetSetup::of(&s.name, &s.output)).collect::<Vec<_>>()).as_bytes())?;
            println!("wrote {}", output.display());
            Ok(())
        }
        Command::Tools { files, inches, to, out } => {
            let main = files.iter().find(|f| f.extension().is_some_and(|e| e == "fctl")).unwrap_or(&files[0]);
            let name = |f: &PathBuf| f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let mut bits = Vec::new();
            for f in files.iter().filter(|f| *f != main) {
                bits.push((name(f), read(f)?));
            }
            let read = swarf::tool::library::read_library(&read(main)?, &name(main), inches, &bits).map_err(|e| e.to_string())?;
            for note in &read.notes {
                eprintln!("note: {note}");
            }
            let text = match to.as_deref() {
                None | Some("swarf") => serde_json::to_string_pretty(&serde_json::json!({ "tools": read.tools })).map_err(|e| e.to_string())?,
                Some("fusion") => swarf::tool::library::write_library(&read.tools, swarf::tool::library::LibraryFormat::Fusion),
                Some("linuxcnc") => swarf::tool::library::write_library(&read.tools, swarf::tool::library::LibraryFormat::LinuxCnc),
                Some("freecad") => {
                    let dir = out.ok_or("--to freecad writes several files: give the folder with --out")?;
                    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
                    let library = dir.file_name().map_or("swarf".into(), |n| n.to_string_lossy().into_owned());
                    for (file, text) in swarf::tool::library::write_freecad(&read.tools, &library) {
                        std::fs::write(dir.join(&file), text).map_err(|e| format!("{}: {e}", dir.join(&file).display()))?;
                    }
                    eprintln!("note: a FreeCAD bit holds no speeds or holder (its tool controller does): they are not written");
                    eprintln!("{} tools read from {}, written to {}", read.tools.len(), main.display(), dir.join(format!("{library}.fctl")).display());
                    return Ok(());
                }
                Some(other) => return Err(format!("--to {other}: give fusion, linuxcnc, freecad or swarf")),
            };
            println!("{}", text.trim_end());
            eprintln!("{} tools read from {}", read.tools.len(), main.display());
            Ok(())
        }
        Command::Job { drawing } => {
            let job = if drawing { Job::default_for_drawing() } else { Job::default() };
            println!("{}", serde_json::to_string_pretty(&job).map_err(|e| e.to_string())?);
            Ok(())
        }
        Command::Drawing { file } => {
            let name = file.file_name().map(|n| n.to_string_lossy().into_owned());
            let d = read_drawing(&read(&file)?, name.as_deref(), &swarf::geom::Tolerances::default()).map_err(|e| format!("{}: {e}", file.display()))?;
            println!("units: {}", d.units);
            println!("layers: {}", d.layers.join(", "));
            for (k, n) in &d.ignored {
                println!("ignored: {n} {k}");
            }
            let nesting = swarf::drawing::Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
            for (i, (l, o)) in d.loops.iter().zip(&nesting.loops).enumerate() {
                let b = l.path.bounds();
                println!(
                    "loop {i}: layer {}, {}, {} entities, ({:.3}, {:.3})–({:.3}, {:.3}) mm",
                    l.layer,
                    if o.is_ccw() { "outside" } else { "hole" },
                    l.path.len(),
                    b.min.x,
                    b.min.y,
                    b.max.x,
                    b.max.y
                );
            }
            for o in &d.open {
                println!("open chain: layer {}, {} entities, from ({:.3}, {:.3}) to ({:.3}, {:.3}) mm", o.layer, o.segments, o.start.x, o.start.y, o.end.x, o.end.y);
            }
            // Its circles: the holes a drilling operation finds, by loop, and by diameter.
            let holes = swarf::holes::in_drawing(&d, 0.0, 0.0);
            for h in &holes {
                let index = h.loop_index.unwrap_or(0);
                let layer = h.layer.as_deref().unwrap_or("");
                if h.mark {
                    println!("drill mark {index}: at ({:.3}, {:.3}) mm, layer {layer}", h.center.x, h.center.y);
                } else {
                    println!("hole (loop {index}): φ{:.3} at ({:.3}, {:.3}) mm, layer {layer}", h.diameter, h.center.x, h.center.y);
                }
            }
            if !holes.is_empty() {
                println!("holes: {}", swarf::machining::holes::sizes(&holes).join(", "));
            }
            Ok(())
        }
        Command::Edges { file, job } => {
            let job = job_or_default(job.as_deref())?;
            let mesh = read_part(&file, &job)?;
            let edges = job.top_edges(mesh).map_err(|e| e.to_string())?;
            for (k, e) in edges.iter().enumerate() {
                let b = e.outline.bounds();
                println!(
                    "edge {k}: the outline of a face at Z{:.3}, {:.1} mm long, X{:.3}..{:.3} Y{:.3}..{:.3}: {}",
                    e.z,
                    e.outline.length(),
                    b.min.x,
                    b.max.x,
                    b.min.y,
                    b.max.y,
                    if e.sharp { "sharp (a chamfer can break it)" } else { "not sharp all round" }
                );
            }
            println!("{} top edges, {} sharp", edges.len(), edges.iter().filter(|e| e.sharp).count());
            Ok(())
        }
        Command::Holes { file, job, bosses: true } => {
            let job = job_or_default(job.as_deref())?;
            let mesh = read_part(&file, &job)?;
            let bosses = job.bosses(mesh).map_err(|e| e.to_string())?;
            for (k, b) in bosses.iter().enumerate() {
                println!("boss {k}: at ({:.3}, {:.3}), φ{:.3}, top {:.3}, bottom {:.3}", b.center.x, b.center.y, b.diameter, b.top, b.bottom);
            }
            println!("{} {}", bosses.len(), if bosses.len() == 1 { "boss" } else { "bosses" });
            Ok(())
        }
        Command::Holes { file, job, bosses: false } => {
            let job = job_or_default(job.as_deref())?;
            let name = file.file_name().map(|n| n.to_string_lossy().into_owned());
            let bytes = read(&file)?;
            let started = Instant::now();
            let workpiece: Workpiece = if swarf::drawing::import::is_drawing(name.as_deref(), &bytes) {
                Workpiece::Drawing(read_drawing(&bytes, name.as_deref(), &job.tolerances).map_err(|e| format!("{}: {e}", file.display()))?)
            } else {
                Workpiece::Mesh(read_mesh_auto(&bytes, name.as_deref(), &job.tolerances).map_err(|e| format!("{}: {e}", file.display()))?)
            };
            let holes = job.holes(workpiece).map_err(|e| e.to_string())?;
            for (k, h) in holes.iter().enumerate() {
                let kind = match (h.through, h.bottom_shape) {
                    (true, _) => "through".to_string(),
                    (false, swarf::holes::Bottom::Cone) => "blind, cone bottom".to_string(),
                    (false, _) => "blind, flat bottom".to_string(),
                };
                let index = h.loop_index.map_or(k, |l| l);
                if h.mark {
                    println!("hole {index}: a drill mark at ({:.3}, {:.3}), top {:.3}, bottom {:.3}, through (drilled as wide as its drill)", h.center.x, h.center.y, h.top, h.bottom);
                    continue;
                }
                println!("hole {index}: φ{:.3} at ({:.3}, {:.3}), top {:.3}, bottom {:.3} ({:.3} deep), {kind}", h.diameter, h.center.x, h.center.y, h.top, h.bottom, h.depth());
            }
            let sizes = swarf::machining::holes::sizes(&holes);
            println!("{} holes{}{} ({:.2} s)", holes.len(), if sizes.is_empty() { "" } else { ": " }, sizes.join(", "), started.elapsed().as_secs_f64());
            Ok(())
        }
        Command::Verify { job, part, program, cell, json } => {
            let job = read_job(&job)?;
            let name = part.file_name().map(|n| n.to_string_lossy().into_owned());
            let mesh = read_mesh_auto(&read(&part)?, name.as_deref(), &job.tolerances).map_err(|e| format!("{}: {e}", part.display()))?;
            let text = String::from_utf8_lossy(&read(&program)?).into_owned();
            let started = Instant::now();
            let v = verify_gcode(&job, mesh, &text, cell, &mut Progress::none()).map_err(|e| format!("{}: {e}", program.display()))?;
            if json {
                println!("{}", serde_json::to_string_pretty(&v.report).unwrap());
            } else {
                print!("{}", v.report.describe());
                println!("({:.2} s)", started.elapsed().as_secs_f64());
            }
            if v.report.is_clean() {
                Ok(())
            } else {
                Err(format!("{}: the program has problems (see above)", program.display()))
            }
        }
        Command::Zmap { part, shape, diameter, corner, angle, tip, grid, builder, units, y_up, center_top, floor, format, output } => {
            not_an_input(&output, &[&part])?;
            let tolerances = Tolerances::default();
            let name = part.file_name().map(|n| n.to_string_lossy().into_owned());
            let mut mesh = read_mesh_auto(&read(&part)?, name.as_deref(), &tolerances).map_err(|e| format!("{}: {e}", part.display()))?;
            let setup = PartSetup {
                units: match units {
                    UnitsArg::Auto => PartUnits::Auto,
                    UnitsArg::Mm => PartUnits::Mm,
                    UnitsArg::Inch => PartUnits::Inch,
                    UnitsArg::M => PartUnits::Metre,
                },
                scale: 1.0,
                up_axis: if y_up { UpAxis::Y } else { UpAxis::Z },
                rotation: 0,
                placement: if center_top { Placement::CenterTop } else { Placement::Keep },
            };
            setup.apply(&mut mesh);
            let cutter = match shape {
                ShapeArg::VBit => Cutter::v_bit(diameter, angle, tip),
                ShapeArg::Flat | ShapeArg::Ball | ShapeArg::BullNose => Cutter {
                    shape: match shape {
                        ShapeArg::Flat => Shape::Flat,
                        ShapeArg::Ball => Shape::Ball,
                        _ => Shape::BullNose,
                    },
                    diameter,
                    corner_radius: corner,
                    ..Cutter::default()
                },
            };
            cutter.validate().map_err(|e| e.to_string())?;
            let b = mesh.bounds();
            let g = Grid::checked(b.min.truncate(), b.max.truncate(), grid)?;
            let floor = floor.unwrap_or(b.min.z);
            let started = Instant::now();
            let field = match builder {
                BuilderArg::Exact => cl_exact(&mesh, &cutter.profile(), g, floor, &tolerances, &mut Progress::none()),
                BuilderArg::Inverse => cl_inverse_offset(&cc_zmap(&mesh, g, floor, &tolerances), &cutter.profile(), &mut Progress::none()),
            }
            .map_err(|e| e.to_string())?;
            eprintln!("{} × {} nodes in {:.3} s", g.nx, g.ny, started.elapsed().as_secs_f64());
            match format {
                FormatArg::Csv => write(&output, io::to_csv(&field).as_bytes()),
                FormatArg::Raw => write(&output, &io::to_raw(&field)),
            }
        }
    }
}

/// How `swarf run` reports.
#[derive(Clone, Copy)]
struct RunOptions {
    quiet: bool,
    write_anyway: bool,
    stage_times: bool,
}

/// Setup `k`'s program beside `output`: named after the part, the setup and the controller
/// (`bracket-op2-grbl.nc`).
fn setup_path(output: &Path, k: usize, job: &Job) -> PathBuf {
    let stem = output.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "part".into());
    let control = match &job.post.custom {
        Some(_) => "custom".to_owned(),
        None => serde_json::to_value(job.post.dialect).ok().and_then(|v| v.as_str().map(str::to_lowercase)).unwrap_or_default(),
    };
    let ext = output.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_else(|| job.post.extension());
    output.with_file_name(format!("{stem}-op{}-{control}.{ext}", k + 1))
}

fn run_job(job: &Job, workpiece: impl Into<Workpiece>, output: &Path, options: RunOptions) -> Result<(), String> {
    let RunOptions { quiet, write_anyway, stage_times } = options;
    let started = Instant::now();
    let mut last = -1i32;
    // Each stage as the progress names it, in the order first met, and its seconds: from each
    // report that enters it to the next report of another stage.
    let mut stages: Vec<(String, f64)> = Vec::new();
    let mut current: Option<usize> = None;
    let mut since = Instant::now();
    let mut sink = |fraction: f64, stage: &str| {
        if stage_times && current.is_none_or(|i| stages[i].0 != stage) {
            match current {
                Some(i) => stages[i].1 += since.elapsed().as_secs_f64(),
                None => stages.push(("(setting up: the part, the stock, the tools)".to_owned(), since.elapsed().as_secs_f64())),
            }
            since = Instant::now();
            current = Some(stages.iter().position(|(s, _)| s == stage).unwrap_or_else(|| {
                stages.push((stage.to_owned(), 0.0));
                stages.len() - 1
            }));
        }
        let percent = (fraction * 100.0) as i32;
        if !quiet && percent != last {
            last = percent;
            eprint!("\r{percent:3}% {stage:<40}");
            let _ = std::io::stderr().flush();
        }
        true
    };
    let workpiece = workpiece.into();
    let outs: Vec<(PathBuf, job::JobOutput)> = if job.setups.is_empty() {
        vec![(output.to_owned(), job::run(job, workpiece, &mut Progress::new(&mut sink)).map_err(|e| e.to_string())?)]
    } else {
        let Workpiece::Mesh(part) = workpiece else { return Err("setups turn a 3D part over; a drawing is cut from one side (a job without setups)".into()) };
        let setups = job::run_setups(job, part, &mut Progress::new(&mut sink)).map_err(|e| e.to_string())?;
        setups.into_iter().enumerate().map(|(k, s)| (setup_path(output, k, job), s.output)).collect()
    };
    if let Some(i) = current {
        stages[i].1 += since.elapsed().as_secs_f64();
    }
    if !quiet {
        eprintln!();
    }
    let mut unsafe_programs = Vec::new();
    for (path, out) in &outs {
        if outs.len() > 1 {
            eprintln!("{}:", path.display());
        }
        for w in &out.warnings {
            // A note for the record is said as one, not as a warning.
            let what = if w.level == swarf::error::Level::Note { "note" } else { "warning" };
            eprintln!("{what}: {w}");
        }
        if out.operations.len() > 1 || out.feeds.is_some() || out.operations.iter().any(|o| o.stages.is_some() || o.load.is_some() || o.engagement.is_some()) {
            for r in &out.operations {
                eprintln!("  {}", r.describe());
            }
        }
        if let Some(f) = &out.feeds {
            eprintln!("{}", f.describe());
        }
        if let Some(v) = &out.verification {
            let r = &v.report;
            eprintln!(
                "simulated on {} cells: {} gouges, {} rapids through stock, {} body collisions; material left {:.3} mm at most",
                r.cells, r.gouge_count, r.rapid_collision_count, r.body_collision_count, r.residual_max
            );
        }
        if let Some(problem) = &out.problem {
            unsafe_programs.push(if outs.len() > 1 { format!("{}: {problem}", path.display()) } else { problem.clone() });
        }
    }
    if !unsafe_programs.is_empty() {
        let problems = unsafe_programs.join("\n");
        if !write_anyway {
            return Err(format!("{problems}\nno program written (pass --write-anyway to write it with a warning at its head)"));
        }
        eprintln!("warning: {problems}\nwritten anyway, with a warning at its head");
    }
    // Every setup in one program, where the job asks for it: written to `output` itself.
    if job.post.one_program && !job.setups.is_empty() {
        let names = job.setup_names();
        let sheets: Vec<_> = outs.iter().zip(&names).map(|((_, out), name)| job::sheet::SheetSetup::of(name, out)).collect();
        let programs: Vec<_> = sheets.iter().zip(&outs).map(|(s, (_, out))| (s, out.gcode.as_str(), out.problem.as_deref())).collect();
        let joined = job::setups::one_program(job, &programs).map_err(|e| e.to_string())?;
        write(output, joined.as_bytes())?;
        let total: f64 = outs.iter().map(|(_, out)| out.cycle.seconds).sum();
        eprintln!("{}: {} setups in one program, an operator stop (M0) between them; cycle time {} {}", output.display(), outs.len(), swarf::post::clock(total), swarf::post::clock_format(total));
        return Ok(());
    }
    for (path, out) in &outs {
        write(path, out.gcode_marked().as_bytes())?;
        let s = out.stats;
        eprintln!(
            "{}: {} moves, {:.0} mm cutting, {:.0} mm rapid ({:.2} s to compute); cycle time {} {}:",
            path.display(),
            s.moves,
            s.feed_length,
            s.rapid_length,
            started.elapsed().as_secs_f64(),
            swarf::post::clock(out.cycle.seconds),
            swarf::post::clock_format(out.cycle.seconds),
        );
        for item in &out.time {
            eprintln!("  {}: {}", item.label, swarf::post::clock(item.seconds as f64));
        }
    }
    if stage_times {
        eprintln!("stage times:");
        for (stage, seconds) in &stages {
            eprintln!("  {seconds:8.3} s  {stage}");
        }
    }
    Ok(())
}
