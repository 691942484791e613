//! The operations a job can hold, one file each: its options (serde, with their defaults),
//! their `validate` and its `plan`, built on [`crate::machining`] and importing no other
//! operation. They are matched in this one place: each kind is a `mod` line and one line of
//! the `operations!` list below (its variant, its options type, its name in job files);
//! everything else goes through the [`Operate`] contract. A new operation is one more file and
//! those two lines.

use serde::{Deserialize, Serialize};

use crate::machining::Operate;

pub mod bore;
pub mod chamfer;
pub mod drill;
pub mod engrave;
pub mod face;
pub mod finish_pencil;
pub mod finish_raster;
pub mod finish_scallop;
pub mod finish_steep_shallow;
pub mod finish_waterline;
pub mod pocket2d;
pub mod profile2d;
pub mod rough_adaptive;
pub mod rough_octree;
pub mod rough_zigzag;
pub mod rough_zlevel;
pub mod thread_mill;
pub mod vcarve;

pub use bore::Bore;
pub use chamfer::{Chamfer, ChamferEdges};
pub use drill::{Drill, DrillCycle, ReturnLevel};
pub use engrave::Engrave;
pub use face::{Face, FacePattern};
pub use finish_pencil::FinishPencil;
pub use finish_raster::{Boundary, FinishRaster};
pub use finish_scallop::FinishScallop;
pub use finish_steep_shallow::FinishSteepShallow;
pub use finish_waterline::FinishWaterline;
pub use pocket2d::Pocket2d;
pub use profile2d::{Profile2d, Side, Tabs};
pub use rough_adaptive::RoughAdaptive;
pub use rough_octree::RoughOctree;
pub use rough_zigzag::{Passes, RoughZigzag};
pub use rough_zlevel::RoughZlevel;
pub use thread_mill::{Hand, ThreadMill};
pub use vcarve::VCarve;

pub use crate::machining::report::{LoadReport, StageReport, StageRole};
pub use crate::machining::settings::{Clearance, Direction, EntryKind, HeightFrom, Heights, LoadControl, Moves, Order, PocketPattern, Roughing, Steps};

macro_rules! operations {
    ($($(#[$doc:meta])* $variant:ident($options:ty) = $kind:literal,)*) => {
        /// One operation of a job.
        #[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
        #[serde(tag = "kind", rename_all = "camelCase")]
        pub enum Operation {
            $($(#[$doc])* $variant($options),)*
        }

        /// Read as JSON first, its `kind` then picking the type its settings are read as
        /// ([`Operation::from_json`]): one reader for each kind whatever the operation is read
        /// from (a job file, the page's job, a project), where serde's own for a tagged enum
        /// is built again for every source, every kind's fields inlined in it (112 KB of the
        /// page's wasm, growing with each kind).
        impl<'de> Deserialize<'de> for Operation {
            fn deserialize<D: serde::Deserializer<'de>>(source: D) -> Result<Operation, D::Error> {
                let value = serde_json::Value::deserialize(source)?;
                Operation::from_json(&value).map_err(serde::de::Error::custom)
            }
        }

        impl Operation {
            /// The operation `value` holds, or what is wrong with it: `kind` missing or not
            /// one of [`Operation::KINDS`], or `field: what is wrong`.
            pub fn from_json(value: &serde_json::Value) -> Result<Operation, String> {
                let kind = match value.get("kind") {
                    Some(serde_json::Value::String(kind)) => kind.as_str(),
                    Some(_) => return Err("kind: a string, one of the operations' kinds".into()),
                    None => return Err(if value.is_object() { "missing field `kind`".into() } else { "an operation is an object of settings with its `kind`".into() }),
                };
                match kind {
                    $($kind => Operation::read::<$options>(value).map(Operation::$variant),)*
                    other => Err(format!("unknown variant `{other}`, expected one of {}", Operation::KINDS.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", "))),
                }
            }

            /// The operation's contract.
            pub fn op(&self) -> &dyn Operate {
                match self {
                    $(Operation::$variant(o) => o,)*
                }
            }

            /// Where an operation's JSON does not fit its kind's type: `field: what is wrong`.
            pub(crate) fn field_error(value: &serde_json::Value) -> Option<String> {
                let kind = value.get("kind")?.as_str()?;
                Operation::KINDS.contains(&kind).then(|| Operation::from_json(value).err()).flatten()
            }

            /// The settings of one kind, read from `value`; what does not fit named by its field.
            fn read<T: serde::de::DeserializeOwned>(value: &serde_json::Value) -> Result<T, String> {
                Operation::read_once::<T>(value).map_err(|e| {
                    e.unwrap_or_else(|whole| {
                        // A field of settings flattened into the kind's own (the heights, the
                        // roughing kinds' shared ones) is named by reading them on their own.
                        let named = |r: Result<(), Result<String, String>>| r.err().and_then(Result::ok);
                        named(Operation::read_once::<crate::machining::settings::Heights>(value).map(drop))
                            .or_else(|| named(Operation::read_once::<crate::machining::settings::Roughing>(value).map(drop)))
                            .or_else(|| named(Operation::read_once::<crate::machining::settings::Moves>(value).map(drop)))
                            .or_else(|| named(Operation::read_once::<crate::machining::settings::Clearance>(value).map(drop)))
                            .unwrap_or(whole)
                    })
                })
            }

            /// `read` without looking further: an error `Ok` where it names its field, `Err`
            /// (the message alone) where a flattened field's path is lost.
            fn read_once<T: serde::de::DeserializeOwned>(value: &serde_json::Value) -> Result<T, Result<String, String>> {
                crate::error::read_value::<T>(value).map_err(|e| match e.path().to_string() {
                    path if path == "." => Err(crate::error::plain(&e.inner().to_string())),
                    path => Ok(format!("{path}: {}", crate::error::plain(&e.inner().to_string()))),
                })
            }

            /// One operation of every kind, with its default settings (the page's forms start
            /// from these, so no default is written twice).
            pub fn defaults() -> Vec<Operation> {
                vec![$(Operation::$variant(<$options>::default())),*]
            }

            /// Every kind's form for the page, in this list's order.
            pub fn forms() -> Vec<crate::machining::form::OperationForm> {
                vec![$({
                    let mut form = <$options as Operate>::form();
                    form.kind = $kind;
                    form.applies = <$options>::default().works().into();
                    form
                }),*]
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
    /// Adaptive roughing: z-level's levels cleared at a constant engagement (issue 59).
    RoughAdaptive(RoughAdaptive) = "roughAdaptive",
    /// Octree multi-tool roughing: the tools chosen from the library, biggest first (seed 000).
    RoughOctree(RoughOctree) = "roughOctree",
    /// Raster finishing on a part's CL z-map (seed 001).
    FinishRaster(FinishRaster) = "finishRaster",
    /// Waterline finishing on a part's steep areas.
    FinishWaterline(FinishWaterline) = "finishWaterline",
    /// Pencil finishing along a part's inside corners, found on its CL z-map (issue 60).
    FinishPencil(FinishPencil) = "finishPencil",
    /// Scallop finishing: passes a constant step apart across the surface for a cusp height
    /// (issue 60).
    FinishScallop(FinishScallop) = "finishScallop",
    /// Steep-and-shallow finishing: waterline on the steep, scallop or raster passes on the
    /// shallow, at one cusp height (issue 60).
    FinishSteepShallow(FinishSteepShallow) = "finishSteepShallow",
    /// Profile around a drawing's loops (seed 003).
    Profile2d(Profile2d) = "profile2d",
    /// Pocket inside a drawing's loops (seed 003).
    Pocket2d(Pocket2d) = "pocket2d",
    /// Engraving along a drawing's lines: open chains and chosen loops, the tool's centre on
    /// the line.
    Engrave(Engrave) = "engrave",
    /// Drilling a drawing's circles or a part's holes: spot, drill, dwell, peck, chip break
    /// (canned cycles where the control has them).
    Drill(Drill) = "drill",
    /// Helical boring of holes wider than the tool.
    Bore(Bore) = "bore",
    /// Chamfering (countersinking) holes' top edges with a V-bit or chamfer mill.
    Chamfer(Chamfer) = "chamfer",
    /// Milling internal threads with a single-form thread mill.
    ThreadMill(ThreadMill) = "threadMill",
    /// Facing the stock's top down to the part's top or by a depth.
    Face(Face) = "face",
    /// V-carving a drawing's regions along their medial axis, flat-bottomed below a depth.
    #[serde(rename = "vcarve")]
    VCarve(VCarve) = "vcarve",
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

    /// A roughing kind's settings of what it leaves and how it cuts.
    pub fn roughing(&self) -> Option<&crate::machining::settings::Roughing> {
        match self {
            Operation::RoughZlevel(o) => Some(&o.roughing),
            Operation::RoughZigzag(o) => Some(&o.roughing),
            Operation::RoughAdaptive(o) => Some(&o.roughing),
            Operation::RoughOctree(o) => Some(&o.roughing),
            _ => None,
        }
    }

    /// The heights it cuts between and moves at: a roughing's and a 3D finishing's own, a 2D
    /// or hole operation's clearance and retract (its top and bottom are its depths).
    pub fn heights(&self) -> Option<crate::machining::settings::Heights> {
        match self {
            Operation::FinishRaster(o) => Some(o.heights),
            Operation::FinishWaterline(o) => Some(o.heights),
            Operation::FinishPencil(o) => Some(o.heights),
            Operation::FinishScallop(o) => Some(o.heights),
            Operation::FinishSteepShallow(o) => Some(o.heights),
            Operation::Face(o) => Some(o.moves.heights()),
            Operation::Drill(o) => Some(o.moves.heights()),
            Operation::Bore(o) => Some(o.moves.heights()),
            Operation::Chamfer(o) => Some(o.moves.heights()),
            Operation::ThreadMill(o) => Some(o.moves.heights()),
            Operation::Engrave(o) => Some(o.moves.heights()),
            Operation::VCarve(o) => Some(o.moves.heights()),
            Operation::Pocket2d(o) => Some(o.moves.heights()),
            Operation::Profile2d(o) => Some(o.moves.heights()),
            _ => self.roughing().map(|r| r.heights),
        }
    }

    /// Whether it plans against the in-process stock, what earlier operations left: every
    /// kind but a roughing with rest roughing off, which plans against the setup's stock as it
    /// came.
    pub fn takes_what_is_left(&self) -> bool {
        self.roughing().is_none_or(|r| r.rest)
    }

    /// Whether it is a 3D finishing, which follows the part's surface down as deep as it goes
    /// (and so must keep its tool's shank above the flutes out of the material: the holder's
    /// bound, [`crate::machining::holders`]).
    pub fn is_finishing(&self) -> bool {
        matches!(self, Operation::FinishRaster(_) | Operation::FinishWaterline(_) | Operation::FinishPencil(_) | Operation::FinishScallop(_) | Operation::FinishSteepShallow(_))
    }
}

#[cfg(test)]
mod tests {
    /// The name a job file gives each kind is the one its JSON carries.
    #[test]
    fn each_kind_is_written_by_its_name() {
        let written: Vec<String> = super::Operation::defaults().iter().map(|op| serde_json::to_value(op).unwrap()["kind"].as_str().unwrap().to_string()).collect();
        assert_eq!(written, super::Operation::KINDS);
    }
}
