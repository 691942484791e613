//! swarf: CAM in Rust and WebAssembly. A part (STL, glTF/GLB, OBJ) goes in; gouge-free tool
//! paths and G-code come out. The same library runs in the browser page (through the thin
//! boundary in `wasm.rs`), as the `swarf` command line, in the tests and in the benchmarks.
//!
//! The pipeline, module by module: [`mesh`] (import and placement) → [`zmap`] (CC and CL
//! z-maps, seed 001) → [`operations`] (tool paths on the CL z-map, each operation one file over the [`machining`] they share) → [`toolpath`] (moves,
//! linking, reduction) → [`post`] (G-code). [`job`] ties them together.
//!
//! # Glossary
//! * **CC** (cutter contact): a point where the cutter touches the part.
//! * **CL** (cutter location): the cutter's tip position. A *CL z-map* holds, at each grid node,
//!   the lowest tip height at which the cutter does not cut into the part.
//! * **z-map**: heights on a regular XY grid ([`zmap::HeightField`]).
//! * **MRR**: material removal rate.
//!
//! # Tolerances
//! All tolerances live in [`geom::Tolerances`]; algorithms take them as parameters.

pub mod cutter;
pub mod cutting;
pub mod drawing;
pub mod error;
pub mod file_kind;
pub mod geom;
pub mod holes;
pub mod job;
pub mod limits;
pub mod machining;
pub mod mesh;
pub mod octree;
pub mod offset;
pub mod operations;
pub mod parallel;
pub mod post;
pub mod progress;
pub mod sim;
pub mod tool;
pub mod toolpath;
pub mod view;
pub mod zigzag;
pub mod zmap;

#[cfg(target_arch = "wasm32")]
pub mod wasm;

pub use error::{Error, Result};
pub use job::{run, Job, JobOutput};
pub use mesh::Mesh;
