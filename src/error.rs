//! One error type for the whole pipeline. Each module has its own enum; `Error` gathers them so
//! the CLI and the page can show a message a user understands.

use thiserror::Error;

pub use crate::mesh::import::ImportError;

/// Anything that can go wrong between a dropped file and G-code.
#[derive(Debug, Error)]
pub enum Error {
    #[error(transparent)]
    Import(#[from] ImportError),
    #[error(transparent)]
    Program(#[from] crate::post::read::ReadError),
    #[error("invalid job: {0}")]
    Job(String),
    /// A job file that does not read: the message names the field by its path.
    #[error("invalid job file: {0}")]
    Input(String),
    #[error("cancelled")]
    Cancelled,
    /// The job would make a program that cuts nothing.
    #[error("nothing to cut: {0}")]
    Nothing(String),
    /// Verification found a gouge, a rapid through stock or the tool's body in material.
    #[error("the program is not safe to run: {0}")]
    Unsafe(String),
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
