//! A job: stock, tools, operations and post settings, as one serde type (`schema.rs`). The
//! same JSON drives the page, the CLI and the tests, read by one strict reader (`read.rs`);
//! [`run()`] turns a job and a part or drawing into tool paths and G-code, reporting progress and
//! stopping when cancelled (`run.rs`).
//!
//! A job is a machining sequence: its operations plan one after the other in one shared
//! [`crate::machining::Context`] (the placed part or drawing, the stock, the safe heights, the
//! tool library, the caches), and after each one its moves are applied to the in-process
//! stock, so the next one enters and links over the material that is really there (DESIGN.md
//! ideas 5 and 6). A pool of workers can make a run's pieces (`pool.rs`); drawings become sheets
//! (`drawing.rs`); each operation is reported (`report.rs`); projects hold a job and its part
//! (`project.rs`); a mesh stock is read and placed in `blank.rs`; swarf brings a few jobs of its
//! own (`demo.rs`).

pub mod blank;
pub mod demo;
pub mod drawing;
pub mod fixtures;
pub mod hold;
pub mod pool;
pub mod project;
pub mod read;
pub mod report;
pub mod run;
pub mod schema;
pub mod setups;
pub mod sheet;
pub mod wire;

pub use self::report::OperationReport;
pub use self::run::{drawing_unit_warning, marked, part_warnings, prepare, run, verify_gcode, warning_lines, JobOutput, Prepared, Running};
pub use self::schema::*;
pub use self::setups::{run_setups, SetupOutput};
pub use crate::operations::{Boundary, FinishRaster, Operation};
pub use crate::tool::Tool;
