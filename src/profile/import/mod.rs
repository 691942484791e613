//! Import.
use crate::geom::Tolerances;
use super::Drawing;
pub fn read_drawing(_b: &[u8], _n: Option<&str>, _t: &Tolerances) -> Result<Drawing, String> { Err("todo".into()) }
