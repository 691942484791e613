//! The jobs swarf brings: the default for a drawing, the demo (the sample part's mould job)
//! and the warm-up an engine runs before the user's first job.

use super::schema::Job;
use crate::cutter::Cutter;
use crate::operations::{FinishRaster, Operation, Profile2d};
use crate::tool::Tool;

impl Job {
    /// The default job for a drawing: a φ3 flat end mill cutting the drawing's parts out of
    /// a 6 mm sheet (holes inside, outlines outside), four tabs a part.
    pub fn default_for_drawing() -> Job {
        let tool = Tool { number: 1, name: "3 mm flat end mill".into(), cutter: Cutter::flat(3.0), feed_rate: 800.0, plunge_rate: 200.0, ..Tool::default() };
        let profile = Profile2d { tabs: crate::operations::Tabs { count: 4, ..Default::default() }, ..Profile2d::default() };
        Job { name: "swarf sheet job".into(), tools: vec![tool], operations: vec![Operation::Profile2d(profile)], ..Job::default() }
    }

    /// The mould job the demo and the page's sample part run: z-level roughing with a φ6 flat
    /// end (leaving 0.5 mm), then a φ6 ball finishing the shallow areas by raster and the steep
    /// ones by waterline.
    pub fn demo() -> Job {
        use crate::operations::FinishWaterline;
        use crate::operations::RoughZlevel;
        let flat = Tool { number: 1, name: "6 mm flat end mill".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::flat(6.0) }, feed_rate: 1200.0, plunge_rate: 300.0, ..Tool::default() };
        let ball = Tool { number: 2, name: "6 mm ball end mill".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::ball(6.0) }, ..Tool::default() };
        let steep = 40.0;
        Job {
            name: "swarf demo".into(),
            tools: vec![flat, ball],
            operations: vec![
                Operation::RoughZlevel(RoughZlevel { name: "rough".into(), tool: 1, ..RoughZlevel::default() }),
                Operation::FinishRaster(FinishRaster { name: "finish shallow".into(), tool: 2, stepover: 0.5, slope_max: Some(steep), ..FinishRaster::default() }),
                Operation::FinishWaterline(FinishWaterline { name: "finish steep".into(), tool: 2, scallop: Some(0.01), slope_min: steep, ..FinishWaterline::default() }),
            ],
            ..Job::default()
        }
    }

    /// The two-sided example's job ([`crate::mesh::sample::two_sided_part`],
    /// `examples/two-sided/`): the top (pocket, dome and the four holes through the corners) in
    /// G54, then the part turned over about X in the vise and its bottom (slot, boss and the
    /// boss's blind hole) in G55. Each side is faced and roughed by z-level with a φ6 flat end,
    /// its holes peck-drilled (φ5.5 from the top, φ4.2 from below), then finished by raster
    /// with a φ6 ball, from a block 3 mm larger each side and 1 mm over and under, zero on the
    /// centre of the part's top in each setup.
    pub fn two_sided() -> Job {
        use super::schema::{Flip, Setup, WorkZero};
        use crate::machining::holes::HolePick;
        use crate::operations::{Drill, DrillCycle, Face, RoughZlevel};
        let demo = Job::demo();
        let drill = |number: u32, d: f64| Tool { number, name: format!("{d} mm drill"), cutter: Cutter { flute_length: 30.0, ..Cutter::drill(d, 118.0) }, ..Tool::default() };
        let ops = |pick: HolePick, tool: u32| {
            vec![
                Operation::Face(Face { tool: 1, ..Face::default() }),
                Operation::RoughZlevel(RoughZlevel { name: "rough".into(), tool: 1, ..RoughZlevel::default() }),
                Operation::Drill(Drill { tool, cycle: DrillCycle::Peck, pick, ..Drill::default() }),
                Operation::FinishRaster(FinishRaster { name: "finish".into(), tool: 2, stepover: 0.6, ..FinishRaster::default() }),
            ]
        };
        let mut tools = demo.tools;
        tools.extend([drill(3, 5.5), drill(4, 4.2)]);
        let mut job = Job { name: "two-sided plate".into(), tools, operations: Vec::new(), ..Job::default() };
        job.stock.margin_xy = 3.0;
        job.stock.margin_top = 1.0;
        job.stock.margin_bottom = 1.0;
        job.stock.zero = Some(WorkZero::default());
        job.setups = vec![
            Setup { name: "top".into(), work_offset: Some("G54".into()), operations: ops(HolePick { min_diameter: Some(5.0), ..HolePick::default() }, 3), ..Setup::default() },
            Setup { name: "bottom".into(), flip: Flip::AboutX, work_offset: Some("G55".into()), operations: ops(HolePick { max_diameter: Some(5.0), ..HolePick::default() }, 4), ..Setup::default() },
        ];
        job
    }

    /// The job swarf.js's engine runs once as it starts, in a worker of its own, on
    /// [`crate::mesh::sample::warm_up_part`] (0.1 s natively, about 0.6 s in a fresh browser):
    /// the demo's three operations with a zigzag roughing between, so that the browser has
    /// compiled (and mostly optimised) the code a user's first job runs before the user asks
    /// for it. Without it that first job runs partly in baseline code: the pocket test's
    /// zigzag 0.16–0.21 s against 0.10 s (BENCHMARKS.md, "The warm-up in a worker of its own").
    pub fn warm_up() -> Job {
        use crate::machining::settings::Roughing;
        use crate::operations::RoughZigzag;
        let mut job = Job::demo();
        job.name = "warm-up".into();
        job.operations.insert(
            1,
            Operation::RoughZigzag(RoughZigzag { name: "zigzag".into(), tool: 1, roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() }, ..RoughZigzag::default() }),
        );
        // Coarse and small: what matters is that each strategy's code runs, not the finish.
        job.tools[0].cutter = Cutter { flute_length: 15.0, ..Cutter::flat(3.0) };
        job.tools[1].cutter = Cutter { flute_length: 15.0, ..Cutter::ball(3.0) };
        for op in &mut job.operations {
            match op {
                Operation::RoughZlevel(o) => (o.roughing.grid, o.steps.stepdown) = (0.5, 2.0),
                Operation::RoughZigzag(o) => (o.roughing.grid, o.steps.stepdown, o.steps.stepover_fraction) = (0.5, 3.0, 0.8),
                Operation::FinishRaster(o) => (o.grid, o.stepover) = (0.5, 2.0),
                Operation::FinishWaterline(o) => (o.grid, o.stepdown, o.scallop) = (0.5, 1.5, None),
                _ => {}
            }
        }
        job
    }
}
