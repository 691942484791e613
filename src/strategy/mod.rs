//! Strategies turn a part (through its CL z-map) into tool paths. Each one keeps the tool tip on
//! or above the CL surface plus its allowance, so none can gouge (DESIGN.md, idea 1).

pub mod finish_raster;
pub mod path2d;
pub mod pocket2d;
pub mod profile2d;
pub mod region;
pub mod walls;
