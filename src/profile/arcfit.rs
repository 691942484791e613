//! Arcs through curves.
