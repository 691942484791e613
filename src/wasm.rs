//! The only file with `#[wasm_bindgen]`: a thin boundary between the page's worker and the same
//! `Job → Program → G-code` path the CLI runs. Jobs cross as plain JS objects (serde), parts as
//! bytes, and large results go back as typed-array views into wasm memory (the worker copies
//! them once, to transfer them to the page).

use wasm_bindgen::prelude::*;

use crate::drawing::Drawing;
use crate::geom::Tolerances;
use crate::job::{self, Job, Workpiece};
use crate::mesh::import::read_mesh_auto;
use crate::mesh::placement::PartSetup;
use crate::mesh::{sample, Mesh};
use crate::progress::Progress;
use crate::view;

#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// Plain JS objects (not `Map`s) for structs, as the page expects.
fn to_js<T: serde::Serialize>(value: &T) -> Result<JsValue, JsError> {
    value.serialize(&serde_wasm_bindgen::Serializer::json_compatible()).map_err(js_error)
}

/// A settings object from the page or a portal (plain JS, as JSON would hold it) read as `T`:
/// through JSON's value and [`crate::error::read_value`], the one reader of swarf's types, so
/// none is built again for JS objects; what does not fit is named by its path.
fn from_js<T: serde::de::DeserializeOwned>(value: JsValue) -> Result<T, String> {
    crate::error::read_value(&value_from_js(value)?).map_err(|e| e.to_string())
}

/// A plain JS object as JSON's value.
fn value_from_js(value: JsValue) -> Result<serde_json::Value, String> {
    serde_wasm_bindgen::from_value(value).map_err(|e| e.to_string())
}

/// A job object as JSON's value, or why it is none.
fn job_value(job: JsValue) -> Result<serde_json::Value, JsError> {
    value_from_js(job).map_err(|e| js_error(format!("the job is not a plain object: {e}")))
}

/// A job object from the page or a portal, read by the one strict reader
/// ([`Job::from_value`]): a misspelt field or a value of the wrong type is named by its path,
/// as `readJob` and `swarf run` name it.
fn job_from_js(job: JsValue) -> Result<Job, JsError> {
    Job::from_value(&job_value(job)?).map_err(js_error)
}

/// Every setting of a job (an object) that does not fit, as `[{ path, message }]`
/// ([`Job::problems_with`]): with `part`, the placed part's bounds (`[minX, minY, minZ, maxX,
/// maxY, maxZ]`, as `loadPart` gives them), also a stock box the part sticks out of; with
/// `holes` (the holes found in the workpiece, as `findHoles` gives them), a hole operation's
/// settings that do not fit its holes. A job that does not read gives its one problem, with the
/// path the reader named.
#[wasm_bindgen(js_name = checkJob)]
pub fn check_job(job: JsValue, part: Option<Vec<f64>>, holes: JsValue) -> Result<JsValue, JsError> {
    let value = job_value(job)?;
    let bounds =
        part.filter(|b| b.len() == 6 && b.iter().all(|v| v.is_finite())).map(|b| crate::geom::Aabb { min: crate::geom::DVec3::new(b[0], b[1], b[2]), max: crate::geom::DVec3::new(b[3], b[4], b[5]) });
    let problems = match Job::from_value(&value) {
        Ok(job) => {
            let holes: Option<Vec<crate::holes::Hole>> =
                if holes.is_null() || holes.is_undefined() { None } else { Some(from_js(holes).map_err(|e| js_error(format!("the holes are not as findHoles gives them: {e}")))?) };
            job.problems_with(job::Known { part: bounds.as_ref(), holes: holes.as_deref() }).into_iter().map(job::Problem::at_field).collect()
        }
        Err(e) => {
            let message = e.to_string();
            let named = message.strip_prefix("unknown fields: ").or_else(|| message.strip_prefix("unknown field: ")).unwrap_or(&message);
            let path = named.split([':', ' ', ';']).next().unwrap_or_default().to_owned();
            vec![job::Problem { path, message }.at_field()]
        }
    };
    to_js(&problems)
}

/// The default job, as the JSON object the page edits.
#[wasm_bindgen(js_name = defaultJob)]
pub fn default_job() -> Result<JsValue, JsError> {
    to_js(&Job::default())
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct Defaults {
    job: Job,
    drawing_job: Job,
    tool: crate::tool::Tool,
    operations: Vec<job::Operation>,
    forms: Vec<crate::machining::form::OperationForm>,
    materials: Vec<crate::cutting::MaterialChoice>,
    machines: Vec<crate::cutting::Machine>,
    holders: Vec<crate::tool::Holder>,
}

/// Every default the page's forms start from: `{ job, drawingJob, tool, operations, forms }`:
/// the mould job for parts ([`Job::demo`]), the sheet job for drawings, one operation of each
/// kind, each kind's form (its fields, in the kinds' order), the stock materials, the
/// built-in machines and holders.
#[wasm_bindgen]
pub fn defaults() -> Result<JsValue, JsError> {
    to_js(&Defaults {
        job: Job::demo(),
        drawing_job: Job::default_for_drawing(),
        tool: crate::tool::Tool::default(),
        operations: job::Operation::defaults(),
        forms: job::Operation::forms(),
        materials: crate::cutting::Material::choices(),
        machines: crate::cutting::Machine::builtin(),
        holders: crate::tool::Holder::builtin(),
    })
}

/// Reads a job file's text as `swarf run` does (every unknown or misspelt field named by its
/// path, newer versions refused) and returns the job as the JSON object the page edits.
#[wasm_bindgen(js_name = readJob)]
pub fn read_job(text: &str) -> Result<JsValue, JsError> {
    to_js(&Job::from_json(text).map_err(js_error)?)
}

/// The built-in sample part, as binary STL.
/// The built-in posts: `[{dialect, post}]`, the post as its JSON data.
#[wasm_bindgen(js_name = builtinPosts)]
pub fn builtin_posts() -> Result<JsValue, JsError> {
    let list: Vec<serde_json::Value> = crate::post::Dialect::ALL.iter().map(|d| serde_json::json!({ "dialect": d, "post": d.post() })).collect();
    to_js(&list)
}

/// Reads a post (JSON) as a user saved it; the error names the field.
#[wasm_bindgen(js_name = readPost)]
pub fn read_post(text: &str) -> Result<JsValue, JsError> {
    let post = crate::post::Post::from_json(text).map_err(|e| js_error(format!("post: {e}")))?;
    to_js(&post)
}

/// A project file (`.swarf.json`) of `job` with the part or drawing in `bytes` embedded.
#[wasm_bindgen(js_name = writeProject)]
pub fn write_project(job: JsValue, name: &str, bytes: &[u8]) -> Result<String, JsError> {
    Ok(crate::job::project::Project::embedded(job_from_js(job)?, name, bytes).to_json())
}

/// Reads a project file: `{job, name, bytes}` (`bytes` null when the project only names its
/// part). Errors name the field.
#[wasm_bindgen(js_name = readProject)]
pub fn read_project(text: &str) -> Result<JsValue, JsError> {
    let project = crate::job::project::Project::from_json(text).map_err(js_error)?;
    let bytes = match project.workpiece.data {
        Some(_) => JsValue::from(js_sys::Uint8Array::from(&project.workpiece_bytes(|_| unreachable!("embedded")).map_err(js_error)?[..])),
        None => JsValue::NULL,
    };
    let out = js_sys::Object::new();
    let set = |k: &str, v: &JsValue| js_sys::Reflect::set(&out, &JsValue::from_str(k), v).map(|_| ()).map_err(|_| js_error("cannot build the project object"));
    set("job", &to_js(&project.job)?)?;
    set("name", &JsValue::from_str(&project.workpiece.name))?;
    set("bytes", &bytes)?;
    Ok(out.into())
}

#[wasm_bindgen(js_name = samplePart)]
pub fn sample_part() -> Vec<u8> {
    sample::demo_part().to_binary_stl()
}

/// The job the page's engine runs once as it starts ([`Job::warm_up`]), as the JSON object a
/// run takes.
#[wasm_bindgen(js_name = warmUpJob)]
pub fn warm_up_job() -> Result<JsValue, JsError> {
    to_js(&Job::warm_up())
}

/// The warm-up's part, as binary STL.
#[wasm_bindgen(js_name = warmUpPart)]
pub fn warm_up_part() -> Vec<u8> {
    sample::warm_up_part().to_binary_stl()
}

/// The built-in sample drawing (a plate with holes and a pocket), as DXF text.
#[wasm_bindgen(js_name = sampleDrawing)]
pub fn sample_drawing() -> Vec<u8> {
    crate::drawing::sample::plate_dxf().into_bytes()
}

/// Whether a file is a drawing (DXF, SVG) rather than a part.
#[wasm_bindgen(js_name = isDrawing)]
pub fn is_drawing(bytes: &[u8], name: &str) -> bool {
    crate::drawing::import::is_drawing(Some(name), bytes)
}

fn read_drawing_js(bytes: &[u8], name: &str, tolerances: &Tolerances) -> Result<Drawing, JsError> {
    crate::drawing::import::read_drawing(bytes, Some(name), tolerances).map_err(|e| js_error(format!("{name}: {e}")))
}

/// Reads a drawing and places it as `setup` (a `DrawingSetup` object) says: a
/// [`view::DrawingView`].
#[wasm_bindgen(js_name = loadDrawing)]
pub fn load_drawing(bytes: &[u8], name: &str, setup: JsValue) -> Result<JsValue, JsError> {
    let setup: crate::job::DrawingSetup = from_js(setup).map_err(js_error)?;
    let mut d = read_drawing_js(bytes, name, &Tolerances::default())?;
    setup.apply(&mut d);
    to_js(&view::DrawingView::of(&d))
}

/// A part read and placed, ready to draw ([`view::PartData`]).
#[wasm_bindgen]
pub struct PartView(view::PartData);

#[wasm_bindgen]
impl PartView {
    /// Triangle corners, xyz per vertex, three vertices per triangle (a view: copy before the
    /// next call into wasm).
    pub fn positions(&self) -> js_sys::Float32Array {
        // SAFETY: the view is read before wasm memory can grow again (the caller copies it).
        unsafe { js_sys::Float32Array::view(&self.0.positions) }
    }
    /// Facet normals, one per vertex.
    pub fn normals(&self) -> js_sys::Float32Array {
        // SAFETY: as above.
        unsafe { js_sys::Float32Array::view(&self.0.normals) }
    }
    /// [minX, minY, minZ, maxX, maxY, maxZ] in mm.
    pub fn bounds(&self) -> Vec<f64> {
        self.0.bounds_array()
    }
    pub fn triangles(&self) -> usize {
        self.0.triangles
    }
    /// Degenerate triangles dropped at import.
    pub fn dropped(&self) -> usize {
        self.0.dropped
    }
    /// What the user should know of the part (`Warning` objects): holes in its surface.
    pub fn warnings(&self) -> Result<JsValue, JsError> {
        to_js(&self.0.warnings)
    }
    /// The placed triangles' identity: the same only for the same triangles in the same place.
    pub fn hash(&self) -> String {
        self.0.hash.clone()
    }
}

fn read_part(bytes: &[u8], name: &str, tolerances: &Tolerances) -> Result<Mesh, JsError> {
    read_mesh_auto(bytes, Some(name), tolerances).map_err(|e| js_error(format!("{name}: {e}")))
}

/// Reads a part and places it as `setup` (a `PartSetup` object) says, with a mesh stock
/// (`stockMesh`, the job's `stock.mesh`) as a job with it places it.
#[wasm_bindgen(js_name = loadPart)]
pub fn load_part(bytes: &[u8], name: &str, setup: JsValue, stock_mesh: JsValue) -> Result<PartView, JsError> {
    let setup: PartSetup = from_js(setup).map_err(js_error)?;
    let mut mesh = read_part(bytes, name, &Tolerances::default())?;
    // Placed as the job places it: with a mesh stock, by the blank's top.
    let mesh_stock: Option<crate::job::blank::MeshFile> = if stock_mesh.is_null() || stock_mesh.is_undefined() { None } else { Some(from_js(stock_mesh).map_err(js_error)?) };
    let mut job = Job { part: setup, ..Job::default() };
    job.stock.mesh = mesh_stock;
    job.place_part(&mut mesh);
    Ok(PartView(view::PartData::of(&mesh)))
}

/// What a job produced ([`view::ResultView`]), kept by the worker for scrubbing and reposting.
#[wasm_bindgen]
pub struct JobResult {
    view: view::ResultView,
    /// The setup it is of, for a job with setups.
    setup: Option<job::wire::SetupPlace>,
    /// The stock it left, where a setup follows to carry it on.
    end: Option<crate::sim::DexelStock>,
    /// What the setup sheet says of it.
    sheet: job::sheet::SheetSetup,
}

/// A `Float32Array` view of `data` (copy it before the next call into wasm).
fn floats(data: &[f32]) -> js_sys::Float32Array {
    // SAFETY: the view is read before wasm memory can grow again (the caller copies it).
    unsafe { js_sys::Float32Array::view(data) }
}

/// A `Uint32Array` view of `data` (copy it before the next call into wasm).
fn counts(data: &[u32]) -> js_sys::Uint32Array {
    // SAFETY: as for `floats`.
    unsafe { js_sys::Uint32Array::view(data) }
}

#[wasm_bindgen]
impl JobResult {
    pub fn gcode(&self) -> String {
        self.view.gcode.clone()
    }
    /// The program as UTF-8 bytes (a view): sent to the page's thread without a copy, the text
    /// made from it only when asked for (a die-sized program is tens of megabytes).
    #[wasm_bindgen(js_name = gcodeBytes)]
    pub fn gcode_bytes(&self) -> js_sys::Uint8Array {
        // SAFETY: as for `floats`.
        unsafe { js_sys::Uint8Array::view(self.view.gcode.as_bytes()) }
    }
    /// The line (0 first) of the program each move ended on (a view).
    #[wasm_bindgen(js_name = moveLines)]
    pub fn move_lines(&self) -> js_sys::Uint32Array {
        counts(&self.view.move_lines)
    }
    /// The same paths written by another post (`post`: the job's `post` object), without
    /// planning again: `{gcode, extension, post, cycle, time, moveLines}`
    /// ([`view::Program::repost`]).
    pub fn repost(&self, post: JsValue) -> Result<JsValue, JsError> {
        let r = self.view.program.repost(&self.settings(post)?).map_err(js_error)?;
        let out = to_js(&r)?;
        js_sys::Reflect::set(&out, &"moveLines".into(), &js_sys::Uint32Array::from(&r.move_lines[..])).map_err(|_| js_error("an object"))?;
        Ok(out)
    }
    /// The job's `post` object as this program is written by it: a setup's program keeps its
    /// setup's work offset (`G55`), whatever the job's post selects.
    fn settings(&self, post: JsValue) -> Result<crate::post::PostSettings, JsError> {
        let mut settings: crate::post::PostSettings = from_js(post).map_err(|e| js_error(format!("invalid post: {e}")))?;
        if self.setup.is_some() {
            settings.work_offset = self.view.program.post.work_offset.clone();
        }
        // The machine's rapids, which the job's post object does not hold.
        settings.rapid_axes = self.view.program.post.rapid_axes;
        Ok(settings)
    }
    /// The program as `post` (the job's `post` object) writes it, without the warning at its
    /// head a program not safe to run has: a setup's part of one program for all
    /// (`oneProgram`).
    pub fn program(&self, post: JsValue) -> Result<String, JsError> {
        let p = &self.view.program;
        let settings = self.settings(post)?;
        Ok(crate::post::write_program(&p.title, &p.paths, &p.tools, p.clearance, &settings).map_err(js_error)?.0)
    }
    /// Why the program is not safe to run, if it is not.
    pub fn problem(&self) -> Option<String> {
        self.view.program.problem.clone()
    }
    /// Cutting moves as line segments: xyz of both ends per segment (a view).
    pub fn feeds(&self) -> js_sys::Float32Array {
        floats(&self.view.segments.feeds)
    }
    /// The operation (its index in the job) of each cutting segment of `feeds` (a view).
    #[wasm_bindgen(js_name = feedOperations)]
    pub fn feed_operations(&self) -> js_sys::Float32Array {
        floats(&self.view.segments.feed_ops)
    }
    /// The tool number of each cutting segment of `feeds` (a view).
    #[wasm_bindgen(js_name = feedTools)]
    pub fn feed_tools(&self) -> js_sys::Float32Array {
        floats(&self.view.segments.feed_tools)
    }
    /// The program move of each cutting segment of `feeds` (a view).
    #[wasm_bindgen(js_name = feedMoves)]
    pub fn feed_moves(&self) -> js_sys::Uint32Array {
        counts(&self.view.segments.feed_moves)
    }
    /// The octants of each stage of octree roughing (seed 000): per box `stage, tool, full
    /// (1: cut by that tool, 0: Partial), minX, minY, minZ, maxX, maxY, maxZ` (a view).
    pub fn octants(&self) -> js_sys::Float32Array {
        floats(&self.view.octants)
    }
    /// Rapid moves as line segments (a view).
    pub fn rapids(&self) -> js_sys::Float32Array {
        floats(&self.view.segments.rapids)
    }
    /// The program move of each segment of `rapids` (a view).
    #[wasm_bindgen(js_name = rapidMoves)]
    pub fn rapid_moves(&self) -> js_sys::Uint32Array {
        counts(&self.view.segments.rapid_moves)
    }
    /// The figures, warnings and reports ([`view::Summary`]).
    pub fn summary(&self) -> Result<JsValue, JsError> {
        to_js(&self.view.summary)
    }
    /// Whether the program was simulated.
    #[wasm_bindgen(js_name = hasSimulation)]
    pub fn has_simulation(&self) -> bool {
        self.view.simulation.is_some()
    }
    /// `[originX, originY, spacing, nx, ny, stockBottom, stockTop, gougeTolerance]`: where the
    /// simulated stock's cell centres stand.
    #[wasm_bindgen(js_name = simGrid)]
    pub fn sim_grid(&self) -> Vec<f64> {
        self.view.simulation.as_ref().map(|s| s.grid.clone()).unwrap_or_default()
    }
    /// The part's surface plus allowance at each cell centre (NaN off the part; a view).
    #[wasm_bindgen(js_name = simPart)]
    pub fn sim_part(&self) -> js_sys::Float32Array {
        self.view.simulation.as_ref().map(|s| floats(&s.part)).unwrap_or_default()
    }
    /// When each move starts (s), and at the end the program's cycle time.
    pub fn times(&self) -> js_sys::Float64Array {
        // SAFETY: as for `floats`.
        self.view.simulation.as_ref().map(|s| unsafe { js_sys::Float64Array::view(&s.times) }).unwrap_or_default()
    }
    /// Material removal rate of each move (mm³/min; a view).
    pub fn mrr(&self) -> js_sys::Float32Array {
        self.view.simulation.as_ref().map(|s| floats(&s.mrr)).unwrap_or_default()
    }
    /// Places of gouges and collisions: x, y, z, kind (0 gouge, 1 rapid, 2 tool body) per place.
    pub fn findings(&self) -> js_sys::Float32Array {
        self.view.simulation.as_ref().map(|s| floats(&s.findings)).unwrap_or_default()
    }
    /// The verification report (`Report` as a JS object, with `text` for people).
    pub fn report(&self) -> Result<JsValue, JsError> {
        self.view.simulation.as_ref().map_or(Ok(JsValue::NULL), |s| to_js(&s.report))
    }
    /// The stock's height over every cell after the first `count` moves (a view: copy it before
    /// the next call).
    pub fn seek(&mut self, count: usize) -> js_sys::Float32Array {
        match self.view.simulation.as_mut() {
            Some(s) => floats(s.playback.seek(count)),
            None => js_sys::Float32Array::default(),
        }
    }
    /// Where the tool is a fraction `f` of the way through move `k`: `[x, y, z, tool]`, empty
    /// without a simulation.
    #[wasm_bindgen(js_name = toolAt)]
    pub fn tool_at(&self, k: usize, f: f64) -> Vec<f64> {
        self.view.tool_at(k, f).map(|t| t.to_vec()).unwrap_or_default()
    }
    /// The drawing as the job placed it (as `loadDrawing` gives it), or null for a part.
    pub fn drawing(&self) -> Result<JsValue, JsError> {
        self.view.drawing.as_ref().map_or(Ok(JsValue::NULL), to_js)
    }
    /// Where the setup this result is of holds the part (`SetupView`, its stock the program's),
    /// or `undefined` for a job without setups.
    pub fn setup(&self) -> Result<JsValue, JsError> {
        match &self.setup {
            Some(s) => to_js(&view::SetupView::of(s.index, &s.name, &s.orientation, self.sheet.stock)),
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// What the setup sheet says of this program ([`job::sheet::SheetSetup`]), for `setupSheet`.
    pub fn sheet(&self) -> Result<JsValue, JsError> {
        to_js(&self.sheet)
    }

    /// The part as the job placed it.
    #[wasm_bindgen(js_name = takePart)]
    pub fn take_part(&mut self) -> PartView {
        PartView(std::mem::replace(&mut self.view.part, view::PartData::empty()))
    }
}

/// The holes a hole operation of `job` finds in the part or drawing in `bytes`, placed as the
/// job places it (with `setup`, as that setup of a job with setups holds it), numbered as the
/// operations' `holes` take them (`swarf holes`).
#[wasm_bindgen(js_name = findHoles)]
pub fn find_holes(job: JsValue, bytes: &[u8], name: &str, setup: Option<usize>) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    let workpiece = Workpiece::read(bytes, Some(name), &job.tolerances).map_err(js_error)?;
    let holes = match (setup, workpiece) {
        (Some(_), Workpiece::Mesh(part)) => {
            let (job, part) = as_held(job, part, setup)?;
            job.holes(part)
        }
        (_, workpiece) => job.holes(workpiece),
    };
    to_js(&holes.map_err(js_error)?)
}

/// `job` (and the part as read), or with `setup` that setup's job and the part held as it
/// holds it: where a setup's operations find what they pick from.
fn as_held(job: Job, part: crate::mesh::Mesh, setup: Option<usize>) -> Result<(Job, crate::mesh::Mesh), JsError> {
    match setup {
        Some(k) => job.for_setup(k, part).map(|(sub, held, _)| (sub, held)).map_err(js_error),
        None => Ok((job, part)),
    }
}

/// The round bosses (studs) an external thread mill of `job` finds on the part in `bytes`,
/// placed as the job places it, numbered as the operation's `holes` take them (`swarf holes
/// --bosses`). A drawing has none: an error says so.
#[wasm_bindgen(js_name = findBosses)]
pub fn find_bosses(job: JsValue, bytes: &[u8], name: &str, setup: Option<usize>) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    let part = mesh_only(bytes, name, &job, "a drawing has no bosses: external threads are milled round a 3D part's round studs")?;
    let (job, part) = as_held(job, part, setup)?;
    to_js(&job.bosses(part).map_err(js_error)?)
}

/// The part's top edges a chamfer of `job` (`edges: partEdges`) finds on the part in `bytes`,
/// placed as the job places it, numbered as its `loops` take them (`swarf edges`). A drawing's
/// edges are its loops: an error says so.
#[wasm_bindgen(js_name = findEdges)]
pub fn find_edges(job: JsValue, bytes: &[u8], name: &str, setup: Option<usize>) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    let part = mesh_only(bytes, name, &job, "a drawing's edges are its loops: chamfer them with edges: loops")?;
    let (job, part) = as_held(job, part, setup)?;
    to_js(&job.top_edges(part).map_err(js_error)?.iter().map(view::EdgeView::of).collect::<Vec<_>>())
}

/// The part in `bytes` as a mesh; a drawing is refused with `why`.
fn mesh_only(bytes: &[u8], name: &str, job: &Job, why: &str) -> Result<crate::mesh::Mesh, JsError> {
    match Workpiece::read(bytes, Some(name), &job.tolerances).map_err(js_error)? {
        Workpiece::Mesh(part) => Ok(part),
        Workpiece::Drawing(_) => Err(JsError::new(why)),
    }
}

/// Runs `job` (a `Job` object) on the part in `bytes`. `progress(fraction, stage)` is called as
/// the work goes on; returning `false` cancels.
#[wasm_bindgen(js_name = runJob)]
pub fn run_job(job: JsValue, bytes: &[u8], name: &str, progress: &js_sys::Function) -> Result<JobResult, JsError> {
    prepare_job(job, bytes, name, None)?.run(progress)
}

/// A job prepared for planning (the part read and placed), whose heavy work a pool of workers
/// can share first: one worker's [`crate::job::wire::PoolWorker`], its pieces converted to and
/// from typed arrays.
#[wasm_bindgen]
pub struct JobPlan(crate::job::wire::PoolWorker);

/// Prepares `job` on the part or drawing in `bytes` (see [`JobPlan`]).
#[wasm_bindgen(js_name = prepareJob)]
pub fn prepare_job(job: JsValue, bytes: &[u8], name: &str, setup: Option<usize>) -> Result<JobPlan, JsError> {
    let job = job_from_js(job)?;
    let workpiece = Workpiece::read(bytes, Some(name), &job.tolerances).map_err(js_error)?;
    let worker = match setup {
        Some(k) => job::wire::PoolWorker::prepare_setup(&job, workpiece, k),
        None if !job.setups.is_empty() => Err(crate::error::Error::Input("a job with setups runs one setup at a time: name the setup".into())),
        None => job::wire::PoolWorker::prepare(job, workpiece),
    };
    Ok(JobPlan(worker.map_err(js_error)?))
}

/// Each tool's speeds and feeds as `job` cuts them (from the stock's material, or as typed),
/// with how they were worked out: `[CuttingData]` ([`crate::cutting`]).
#[wasm_bindgen(js_name = cuttingData)]
pub fn cutting_data(job: JsValue) -> Result<JsValue, JsError> {
    to_js(&job_from_js(job)?.cutting_data())
}

/// A FreeCAD bit given with its library, or a file of a library written, as text.
#[derive(serde::Deserialize, serde::Serialize)]
struct BitFile {
    name: String,
    text: String,
}

/// Reads a tool library (Fusion's JSON, a LinuxCNC `.tbl`, a FreeCAD `.fctb`, or a `.fctl`
/// with its bits given in `bits` as `[{ name, text }]`): `{ tools, notes }`
/// ([`crate::tool::library::read_library`]); `inches` reads a tool table in inches.
#[wasm_bindgen(js_name = readToolLibrary)]
pub fn read_tool_library(bytes: &[u8], name: &str, inches: bool, bits: JsValue) -> Result<JsValue, JsError> {
    let bits: Vec<BitFile> = if bits.is_undefined() || bits.is_null() { Vec::new() } else { from_js(bits).map_err(|e| js_error(format!("bits: {e}")))? };
    let bits: Vec<(String, Vec<u8>)> = bits.into_iter().map(|b| (b.name, b.text.into_bytes())).collect();
    to_js(&crate::tool::library::read_library(bytes, name, inches, &bits).map_err(js_error)?)
}

/// `tools` (swarf's, as a job holds them) as a library of `format` (`fusion` or `linuxCnc`).
#[wasm_bindgen(js_name = writeToolLibrary)]
pub fn write_tool_library(tools: JsValue, format: JsValue) -> Result<String, JsError> {
    let tools: Vec<crate::tool::Tool> = from_js(tools).map_err(|e| js_error(format!("tools: {e}")))?;
    let format: crate::tool::library::LibraryFormat = from_js(format).map_err(|e| js_error(format!("format: {e}")))?;
    Ok(crate::tool::library::write_library(&tools, format))
}

/// `tools` as a FreeCAD library named `library`: `[{ name, text }]`, its `.fctl` first, then a
/// `.fctb` bit a tool ([`crate::tool::library::write_freecad`]).
#[wasm_bindgen(js_name = writeFreecadLibrary)]
pub fn write_freecad_library(tools: JsValue, library: &str) -> Result<JsValue, JsError> {
    let tools: Vec<crate::tool::Tool> = from_js(tools).map_err(|e| js_error(format!("tools: {e}")))?;
    let files: Vec<BitFile> = crate::tool::library::write_freecad(&tools, library).into_iter().map(|(name, text)| BitFile { name, text }).collect();
    to_js(&files)
}

/// Every setup of `job` in one program (`post.oneProgram`), an operator stop between them:
/// from each setup's result's `sheet()`, `program(job.post)` and `problem()` in order. A
/// program not safe to run has the warning of each setup that is not at its head.
#[wasm_bindgen(js_name = oneProgram)]
pub fn one_program(job: JsValue, sheets: JsValue, programs: Vec<String>, problems: Vec<String>) -> Result<String, JsError> {
    let job = job_from_js(job)?;
    let sheets: Vec<job::sheet::SheetSetup> = from_js(sheets).map_err(|e| js_error(format!("the sheets are not as results give them: {e}")))?;
    if sheets.len() != programs.len() || problems.len() != programs.len() {
        return Err(js_error("one sheet, one program and one problem (empty: none) a setup"));
    }
    let parts: Vec<_> = sheets.iter().zip(&programs).zip(&problems).map(|((s, g), p)| (s, g.as_str(), Some(p.as_str()).filter(|p| !p.is_empty()))).collect();
    job::setups::one_program(&job, &parts).map_err(js_error)
}

/// The setup sheet (a standalone HTML page) of `job` on the part named `part`, from each
/// setup's result's `sheet()` in order (one for a job without setups).
#[wasm_bindgen(js_name = setupSheet)]
pub fn setup_sheet(job: JsValue, part: &str, sheets: JsValue) -> Result<String, JsError> {
    let job = job_from_js(job)?;
    let sheets: Vec<job::sheet::SheetSetup> = from_js(sheets).map_err(|e| js_error(format!("the sheets are not as results give them: {e}")))?;
    Ok(job::sheet::setup_sheet(&job, part, &sheets))
}

/// The work zero of `job` (or of its setup `setup`) with X0 Y0 on the point `(x, y)` where it
/// holds the part now (a hole's centre as `findHoles` gives it), its height kept
/// ([`Job::zero_on`]); `part` is the part's bounds as `setupFrames` takes them.
#[wasm_bindgen(js_name = zeroOn)]
pub fn zero_on(job: JsValue, part: Vec<f64>, setup: Option<usize>, x: f64, y: f64) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    to_js(&job.zero_on(&bounds_of(&part)?, setup, crate::geom::DVec2::new(x, y)).map_err(js_error)?)
}

/// Six numbers as a box (min then max corner).
fn bounds_of(part: &[f64]) -> Result<crate::geom::Aabb, JsError> {
    if part.len() != 6 || part.iter().any(|v| !v.is_finite()) {
        return Err(js_error("the part's bounds are six numbers"));
    }
    Ok(crate::geom::Aabb { min: crate::geom::DVec3::new(part[0], part[1], part[2]), max: crate::geom::DVec3::new(part[3], part[4], part[5]) })
}

/// Where each setup of `job` holds a part whose bounds (placed as the job places it) are `part`
/// (`[minX, minY, minZ, maxX, maxY, maxZ]`, as `loadPart` gives them): `[SetupView]`, empty
/// for a job without setups.
/// How the view shows `job` before it runs ([`view::SetupView::stage`]): each setup's frame,
/// or the job's one, with its stock box and fixtures; `part` is the part's bounds as
/// `loadPart` placed it.
#[wasm_bindgen(js_name = stageFrames)]
pub fn stage_frames(job: JsValue, part: Vec<f64>) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    to_js(&view::SetupView::stage(&job, &bounds_of(&part)?))
}

#[wasm_bindgen(js_name = setupFrames)]
pub fn setup_frames(job: JsValue, part: Vec<f64>) -> Result<JsValue, JsError> {
    let job = job_from_js(job)?;
    to_js(&view::SetupView::frames(&job, &bounds_of(&part)?))
}

#[wasm_bindgen]
impl JobPlan {
    /// What can be shared: `{ surfaces: [{ nx, ny }], rasters: [{ operation, surface, passes }],
    /// levelMaps: [surface] }` ([`crate::job::wire::PlanNeeds`]).
    /// Starts from the stock the setup before left (`before`, its result): before planning.
    #[wasm_bindgen(js_name = carryFrom)]
    pub fn carry_from(&mut self, before: &JobResult) -> Result<(), JsError> {
        let (Some(left), Some(place)) = (&before.end, &before.setup) else { return Err(js_error("that result leaves no stock to carry on (it is not of a setup another follows)")) };
        self.0.carry_from(left, &place.orientation).map_err(js_error)
    }

    pub fn needs(&mut self) -> Result<JsValue, JsError> {
        to_js(&self.0.needs().map_err(js_error)?)
    }

    #[wasm_bindgen(js_name = levelRows)]
    pub fn level_rows(&mut self, k: usize, j0: usize, j1: usize) -> Result<Vec<f64>, JsError> {
        self.0.level_rows(k, j0, j1).map_err(js_error)
    }

    #[wasm_bindgen(js_name = keepLevelMap)]
    pub fn keep_level_map(&mut self, k: usize, right: Vec<f64>, up: Vec<f64>, wide: Vec<f64>) -> Result<(), JsError> {
        self.0.keep_level_map(k, right, up, wide).map_err(js_error)
    }

    #[wasm_bindgen(js_name = surfaceRows)]
    pub fn surface_rows(&mut self, k: usize, j0: usize, j1: usize) -> Result<Vec<f64>, JsError> {
        self.0.surface_rows(k, j0, j1).map_err(js_error)
    }

    #[wasm_bindgen(js_name = keepSurface)]
    pub fn keep_surface(&mut self, k: usize, z: Vec<f64>) -> Result<(), JsError> {
        self.0.keep_surface(k, z).map_err(js_error)
    }

    #[wasm_bindgen(js_name = rasterPasses)]
    pub fn raster_passes(&mut self, operation: usize, i0: usize, i1: usize) -> Result<Vec<f64>, JsError> {
        self.0.raster_passes(operation, i0, i1).map_err(js_error)
    }

    #[wasm_bindgen(js_name = keepPasses)]
    pub fn keep_passes(&mut self, operation: usize, first: usize, count: usize, flat: &[f64]) -> Result<(), JsError> {
        self.0.keep_passes(operation, first, count, flat).map_err(js_error)
    }

    pub fn release(&mut self) {
        self.0.release();
    }

    pub fn start(&mut self) -> Result<(), JsError> {
        self.0.start().map_err(js_error)
    }

    /// `undefined` once all are planned, else how many moves wait to cut the stock.
    #[wasm_bindgen(js_name = planNext)]
    pub fn plan_next(&mut self, progress: &js_sys::Function) -> Result<Option<usize>, JsError> {
        let mut sink = progress_sink(progress);
        self.0.plan_next(&mut Progress::new(&mut sink)).map_err(js_error)
    }

    /// `{ surface, levels, keep }` ([`crate::job::wire::LevelWork`]), or `undefined`.
    #[wasm_bindgen(js_name = regionWork)]
    pub fn region_work(&mut self) -> Result<JsValue, JsError> {
        let Some(work) = self.0.region_work().map_err(js_error)? else { return Ok(JsValue::UNDEFINED) };
        let out = js_sys::Object::new();
        let set = |k: &str, v: &JsValue| js_sys::Reflect::set(&out, &k.into(), v).map(|_| ()).map_err(|_| js_error("an object"));
        set("surface", &JsValue::from_f64(work.surface as f64))?;
        set("levels", &js_sys::Float64Array::from(&work.levels[..]))?;
        set("keep", &js_sys::Uint8Array::from(&work.keep[..]))?;
        Ok(out.into())
    }

    #[wasm_bindgen(js_name = levelRegions)]
    pub fn level_regions(&mut self, k: usize, levels: &[f64], keep: &[u8]) -> Result<Vec<f64>, JsError> {
        self.0.level_regions(k, levels, keep).map_err(js_error)
    }

    #[wasm_bindgen(js_name = keepRegions)]
    pub fn keep_regions(&mut self, flat: &[f64]) -> Result<(), JsError> {
        self.0.keep_regions(flat).map_err(js_error)
    }

    #[wasm_bindgen(js_name = pendingMoves)]
    pub fn pending_moves(&mut self) -> Result<Vec<f64>, JsError> {
        self.0.pending_moves().map_err(js_error)
    }

    #[wasm_bindgen(js_name = takeBands)]
    pub fn take_bands(&mut self, groups: usize) -> Result<js_sys::Array, JsError> {
        let out = js_sys::Array::new();
        for group in self.0.take_bands(groups).map_err(js_error)? {
            out.push(&js_sys::Float64Array::from(&group[..]));
        }
        Ok(out)
    }

    #[wasm_bindgen(js_name = keepMoves)]
    pub fn keep_moves(&mut self, flat: &[f64]) -> Result<(), JsError> {
        self.0.keep_moves(flat).map_err(js_error)
    }

    /// `[bands, cuts]`, both flat.
    #[wasm_bindgen(js_name = cutBands)]
    pub fn cut_bands(&mut self, group: &[f64]) -> Result<js_sys::Array, JsError> {
        let (bands, cuts) = self.0.cut_bands(group).map_err(js_error)?;
        let out = js_sys::Array::new();
        out.push(&js_sys::Float64Array::from(&bands[..]));
        out.push(&js_sys::Float64Array::from(&cuts[..]));
        Ok(out)
    }

    pub fn absorb(&mut self, groups: Vec<js_sys::Float64Array>, cuts: Vec<js_sys::Float64Array>) -> Result<(), JsError> {
        let groups: Vec<Vec<f64>> = groups.iter().map(|g| g.to_vec()).collect();
        let cuts: Vec<Vec<f64>> = cuts.iter().map(|c| c.to_vec()).collect();
        self.0.absorb(&groups, &cuts).map_err(js_error)
    }

    pub fn finish(&mut self, progress: &js_sys::Function) -> Result<JobResult, JsError> {
        let mut sink = progress_sink(progress);
        let out = self.0.finish(&mut Progress::new(&mut sink)).map_err(js_error)?;
        job_result(&self.0, out)
    }

    /// Plans the job with what was kept and writes its program (see [`run_job`]).
    pub fn run(&mut self, progress: &js_sys::Function) -> Result<JobResult, JsError> {
        let mut sink = progress_sink(progress);
        let out = self.0.run(&mut Progress::new(&mut sink)).map_err(js_error)?;
        job_result(&self.0, out)
    }
}

/// A progress sink calling `progress(fraction, stage)`; the function's `false` cancels.
fn progress_sink(progress: &js_sys::Function) -> impl FnMut(f64, &str) -> bool + '_ {
    |fraction: f64, stage: &str| progress.call2(&JsValue::NULL, &JsValue::from_f64(fraction), &JsValue::from_str(stage)).map(|v| v.as_bool() != Some(false)).unwrap_or(true)
}

/// What the worker hands the page of a job's output (of `worker`'s setup, if any).
fn job_result(worker: &job::wire::PoolWorker, mut out: job::JobOutput) -> Result<JobResult, JsError> {
    let setup = worker.setup().cloned();
    if let Some(s) = &setup {
        out.zero_at = s.zero_at;
    }
    let end = setup.as_ref().filter(|s| s.more).and_then(|_| out.verification.as_ref().map(|v| v.stock.clone()));
    let sheet = job::sheet::SheetSetup::of(setup.as_ref().map_or(&worker.job().name, |s| &s.name), &out);
    Ok(JobResult { view: view::ResultView::of(worker.job(), out), setup, end, sheet })
}
