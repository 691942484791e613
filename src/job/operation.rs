//! The operations a job can hold, matched in this one place: each kind is one line of the
//! `operations!` list below (its variant, its options type beside its strategy, its name in job
//! files); everything else goes through the [`Operate`] contract.

use serde::{Deserialize, Serialize};

use crate::strategy::engrave::Engrave;
use crate::strategy::finish_raster::FinishRaster;
use crate::strategy::finish_waterline::FinishWaterline;
use crate::strategy::pocket2d::Pocket2d;
use crate::strategy::profile2d::Profile2d;
use crate::strategy::rough_octree::RoughOctree;
use crate::strategy::rough_zigzag::RoughZigzag;
use crate::strategy::rough_zlevel::RoughZlevel;
use crate::strategy::Operate;

macro_rules! operations {
    ($($(#[$doc:meta])* $variant:ident($options:ty) = $kind:literal,)*) => {
        /// One operation of a job.
        #[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
        #[serde(tag = "kind", rename_all = "camelCase")]
        pub enum Operation {
            $($(#[$doc])* $variant($options),)*
        }

        impl Operation {
            /// The operation's contract.
            pub fn op(&self) -> &dyn Operate {
                match self {
                    $(Operation::$variant(o) => o,)*
                }
            }

            /// Where an operation's JSON does not fit its kind's type: `field: what is wrong`.
            pub(crate) fn field_error(value: &serde_json::Value) -> Option<String> {
                fn at<T: serde::de::DeserializeOwned>(value: &serde_json::Value) -> Option<String> {
                    serde_path_to_error::deserialize::<_, T>(value).err().map(|e| format!("{}: {}", e.path(), super::read::plain(&e.inner().to_string())))
                }
                match value.get("kind")?.as_str()? {
                    $($kind => at::<$options>(value),)*
                    _ => None,
                }
            }

            /// One operation of every kind, with its default settings (the page's forms start
            /// from these, so no default is written twice).
            pub fn defaults() -> Vec<Operation> {
                vec![$(Operation::$variant(<$options>::default())),*]
            }

            /// The kinds a job file may name.
            pub const KINDS: &'static [&'static str] = &[$($kind),*];
        }
    };
}

operations! {
    /// Z-level roughing on a part's CL z-map (DESIGN.md ideas 1 and 3).
    RoughZlevel(RoughZlevel) = "roughZlevel",
    /// Zigzag roughing by the intersection-points graph, with the load held constant (seed 004).
    RoughZigzag(RoughZigzag) = "roughZigzag",
    /// Octree multi-tool roughing: the tools chosen from the library, biggest first (seed 000).
    RoughOctree(RoughOctree) = "roughOctree",
    /// Raster finishing on a part's CL z-map (seed 001).
    FinishRaster(FinishRaster) = "finishRaster",
    /// Waterline finishing on a part's steep areas.
    FinishWaterline(FinishWaterline) = "finishWaterline",
    /// Profile around a drawing's loops (seed 003).
    Profile2d(Profile2d) = "profile2d",
    /// Pocket inside a drawing's loops (seed 003).
    Pocket2d(Pocket2d) = "pocket2d",
    /// Engraving along a drawing's lines: open chains and chosen loops, the tool's centre on
    /// the line.
    Engrave(Engrave) = "engrave",
}

impl Operation {
    pub fn name(&self) -> &str {
        self.op().name()
    }

    pub fn tool(&self) -> u32 {
        self.op().tool()
    }

    pub fn allowance(&self) -> f64 {
        self.op().allowance()
    }
}
