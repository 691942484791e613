//! Z-level roughing (DESIGN.md ideas 1 and 3): level by level, each level's region cleared by
//! rings inside-out and its boundary last, regions down to their floors one after the other
//! ([`crate::machining::levels`] holds the machinery, shared with zigzag and octree roughing).

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::machining::levels::{level_work, LevelRoughing};
use crate::machining::settings::{Order, Roughing, Steps};
use crate::machining::{named_operation, Context, FieldError, Operate, Planned};
use crate::progress::Progress;

/// Z-level roughing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct RoughZlevel {
    /// Default value: "z-level rough".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// The tool that cuts every level. Default value: 1.
    pub tool: u32,
    /// How deep the levels go and how far apart the rings are.
    #[serde(flatten)]
    #[ts(flatten)]
    pub steps: Steps,
    #[serde(flatten)]
    #[ts(flatten)]
    pub roughing: Roughing,
    /// Helix radius (mm). Default value: 0.4 × the tool diameter.
    pub helix_radius: Option<f64>,
    /// Cut every flat area of the part at its own height too. Default value: true.
    pub flats: bool,
    /// Which comes first: each region down to its floor before the next (`regions`: the tool
    /// goes from pocket to pocket once, not once per level), or each level everywhere before
    /// the next (`levels`). Default value: regions.
    pub order: Order,
}

impl Default for RoughZlevel {
    fn default() -> Self {
        RoughZlevel { name: "z-level rough".into(), enabled: true, tool: 1, steps: Steps::default(), roughing: Roughing::default(), helix_radius: None, flats: true, order: Order::Regions }
    }
}

impl RoughZlevel {
    /// Its levels' settings.
    pub fn levels(&self) -> LevelRoughing {
        LevelRoughing { helix_radius: self.helix_radius, flats: self.flats, order: self.order, ..LevelRoughing::new(&self.name, self.tool, self.steps, &self.roughing) }
    }
}

impl Operate for RoughZlevel {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = crate::machining::settings::roughing_form();
        fields.extend([
            F::choice("order", "Order", &[("regions", "each pocket down to its floor"), ("levels", "level by level")]),
            F::length("helixRadius", "Helix radius", 0.01).empty("0.4 × the tool's diameter"),
        ]);
        OperationForm::new("rough in levels", fields).hint(crate::machining::settings::REST_HINT)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.steps.stepdown)
    }

    fn allowance(&self) -> f64 {
        self.roughing.allowance()
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.levels().validate()
    }

    level_work!();

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let levels = self.levels();
        let Some(cut) = levels.levels_to_cut(ctx, progress)? else { return Ok(Planned::default()) };
        Ok(vec![levels.clear(ctx, cut, progress)?].into())
    }
}
