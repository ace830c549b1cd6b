//! Lesson 07, depth clamp and infinite extrusion: the far plane at
//! infinity, and what each choice costs in depth precision.

pub mod infinite_far;
pub mod precision_study;
pub mod precision_table;
pub mod reversed_z;
