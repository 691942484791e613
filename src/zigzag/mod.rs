//! Seed 004: direction-parallel (zigzag) roughing by the intersection-points graph
//! ([`graph`]), with the tool's load kept at the step-over's by extra path where the plain
//! path would overload it ([`load`], on a pixel map of the level: §3).

pub mod graph;
pub mod load;
