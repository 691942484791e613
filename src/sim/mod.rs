//! Cutting simulation (seed 002): stock models that remove what each move of a program sweeps,
//! and report the volume each move removed. Verification ([`verify`]), the page's simulated
//! stock, rest material for roughing and seed 004's constant-MRR correction all stand on them.
//!
//! * [`dexel::DexelStock`]: the z-map, conventional (`k = 1`) or enhanced (supersampled where a
//!   cut's wall crosses a cell, §3.2).
//! * [`octree::OctreeStock`]: the octree, classical (`k = 1`) or with supersampling at its
//!   boundary leaves (§3.3).
//!
//! All of them ask one question of a move, answered exactly in [`sweep`]: how low does the
//! cutter reach over this point?

pub mod dexel;
pub mod feeds;
pub mod fixtures;
pub mod hold;
pub mod octree;
pub mod paper;
pub mod playback;
pub mod program;
pub mod sweep;
pub mod verify;
pub mod windows;

pub use dexel::DexelStock;
pub use octree::OctreeStock;
pub use sweep::Sweep;

/// A stock that moves cut.
pub trait StockModel {
    /// Removes what `sweep` cuts and returns the volume removed (mm³).
    fn apply(&mut self, sweep: &Sweep) -> f64;
    /// The volume of material left (mm³).
    fn volume(&self) -> f64;
}

/// The four models of seed 002's comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Model {
    /// Conventional z-map.
    Zmap,
    /// Z-map with supersampling (enhanced z-map).
    EnhancedZmap,
    /// Classical octree.
    Octree,
    /// Octree with supersampling.
    SupersampledOctree,
}

/// Sub-samples per side where a model supersamples (seed 002 Fig. 4 uses 2 to 4).
pub const SUPERSAMPLES: usize = 8;

impl Model {
    pub const ALL: [Model; 4] = [Model::Zmap, Model::EnhancedZmap, Model::Octree, Model::SupersampledOctree];

    pub fn label(self) -> &'static str {
        match self {
            Model::Zmap => "z-map",
            Model::EnhancedZmap => "enhanced z-map",
            Model::Octree => "octree",
            Model::SupersampledOctree => "octree + supersampling",
        }
    }

    /// A box stock of this model with cells (or leaves) of side `cell`.
    pub fn stock(self, stock: &crate::geom::Aabb, cell: f64) -> Box<dyn StockModel> {
        match self {
            Model::Zmap => Box::new(DexelStock::new(stock, cell, 1)),
            Model::EnhancedZmap => Box::new(DexelStock::new(stock, cell, SUPERSAMPLES)),
            Model::Octree => Box::new(OctreeStock::new(stock, cell, 1)),
            Model::SupersampledOctree => Box::new(OctreeStock::new(stock, cell, SUPERSAMPLES)),
        }
    }
}
