//! Adaptive roughing (issue 59): z-level roughing's levels (each level's region from the exact
//! CL z-map, flats at their height, the in-process stock as the material), each cleared by
//! adaptive clearing ([`crate::machining::adaptive`]): the tool held at the engagement angle of
//! a light step-over, deep, spiralling out from a helix, its region's boundary last.

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::machining::adaptive::{Adaptive, StepRange};
use crate::machining::levels::{level_work, LevelRoughing};
use crate::machining::settings::{Order, PocketPattern, Roughing, Steps};
use crate::machining::{named_operation, Context, FieldError, Operate, Planned};
use crate::progress::Progress;

/// Adaptive roughing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct RoughAdaptive {
    /// Default value: "adaptive rough".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// The tool that cuts every level. Default value: 1.
    pub tool: u32,
    /// Largest depth between levels (mm): up to the flute length. Default value: 6.
    pub stepdown: f64,
    /// The optimal load: the radial engagement as a fraction of the tool diameter, held all
    /// along the path. Default value: 0.1.
    pub stepover_fraction: f64,
    #[serde(flatten)]
    #[ts(flatten)]
    pub roughing: Roughing,
    /// Helix radius (mm). Default value: 0.4 × the tool diameter.
    pub helix_radius: Option<f64>,
    /// The shortest step of the path (mm), where it turns: each step's heading is searched
    /// there for the target engagement (shorter or longer than the default, passes end sooner:
    /// BENCHMARKS.md). Default value: 0.1 × the tool's radius (at most half the radius; no
    /// finer than two pixels of the map the engagement is read on).
    pub min_step: Option<f64>,
    /// The longest step of the path (mm), along a run that holds the engagement at one
    /// curvature (a spiral, a wall): a step there is twice the last, up to this, and the
    /// shortest again where the engagement no longer holds. Default value: 0.1 × the tool's
    /// radius, or the shortest step where that is longer (at most half the radius).
    pub max_step: Option<f64>,
    /// Cut every flat area of the part at its own height too. Default value: true.
    pub flats: bool,
    /// Which comes first: each region down to its floor before the next (`regions`), or each
    /// level everywhere before the next (`levels`). Default value: regions.
    pub order: Order,
}

impl Default for RoughAdaptive {
    fn default() -> Self {
        RoughAdaptive {
            name: "adaptive rough".into(),
            enabled: true,
            tool: 1,
            stepdown: 6.0,
            stepover_fraction: 0.1,
            roughing: Roughing::default(),
            helix_radius: None,
            min_step: None,
            max_step: None,
            flats: true,
            order: Order::Regions,
        }
    }
}

impl RoughAdaptive {
    /// Its levels' settings.
    pub fn levels(&self) -> LevelRoughing {
        let steps = Steps { stepdown: self.stepdown, stepover_fraction: self.stepover_fraction };
        let adaptive_steps = StepRange { min: self.min_step, max: self.max_step };
        LevelRoughing {
            helix_radius: self.helix_radius,
            flats: self.flats,
            order: self.order,
            pattern: PocketPattern::Adaptive,
            adaptive_steps,
            ..LevelRoughing::new(&self.name, self.tool, steps, &self.roughing)
        }
    }
}

impl Operate for RoughAdaptive {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([F::length("stepdown", "Step-down (up to the flutes)", 0.01), F::fraction("stepoverFraction", "Optimal load", "fraction of the tool's diameter", 1.0)]);
        fields.extend(Roughing::fields());
        fields.extend([
            F::check("flats", "also cut every flat at its own height"),
            F::choice("order", "Order", &[("regions", "each pocket down to its floor"), ("levels", "level by level")]),
            F::length("helixRadius", "Helix radius", 0.01).empty("0.4 × the tool's diameter"),
            F::length("minStep", "Shortest step", 0.001)
                .empty("0.1 × the tool's radius")
                .help("where the path turns: each step's heading is searched for the engagement. A tenth of the radius suits most tools: a shorter step cannot turn far enough from a front in one step, so more passes end early (and a far shorter one can stop the planner with material left, which it warns of); a longer one leaves more behind"),
            F::length("maxStep", "Longest step", 0.001)
                .empty("0.1 × the tool's radius")
                .help("along a run that holds the engagement (a spiral, a wall), steps grow to this; up to half the tool's radius"),
        ]);
        OperationForm::new("adaptive clearing", fields).hint(
            "The tool stays at the engagement of the optimal load all along: a light cut at a deep step-down, spiralling out from a helix, looping into corners instead of slotting; a level shallower than the step-down (a flat, the last) cuts wider by as much. With rest roughing on (the default), after a larger tool it cuts only what that tool left.",
        )
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.stepdown)
    }

    fn allowance(&self) -> f64 {
        self.roughing.allowance()
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.levels().validate()?;
        crate::machining::adaptive::check_load(self.stepover_fraction)
    }

    level_work!();

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let levels = self.levels();
        let Some(cut) = levels.levels_to_cut(ctx, progress)? else { return Ok(Planned::default()) };
        let r = ctx.tool(&self.name, self.tool)?.cutter.radius();
        let ae = (2.0 * r * self.stepover_fraction).min(2.0 * r);
        let angle = Adaptive::angle_of(ae, r);
        // The levels shallower than the step-down, held wider.
        let shallow = cut.levels.iter().map(|l| (l.z, Adaptive::shallow_step(ae, self.stepdown, l.z_prev - l.z, r))).filter(|l| l.1 > ae).map(|(z, wide)| (z, Adaptive::angle_of(wide, r))).collect();
        let engagement = Some(crate::machining::report::EngagementTarget { angle, climb: self.roughing.direction == crate::machining::settings::Direction::Climb, levels: shallow });
        Ok(Planned { engagement, ..vec![levels.clear(ctx, cut, progress)?].into() })
    }
}
