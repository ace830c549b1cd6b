//! Lesson 08, depth bounds and scissor: the light's range sphere on screen
//! and in depth, and the depth-bounds test emulated with a stencil bit.

pub mod bounds_test;
pub mod costs;
pub mod count_bits;
pub mod range_sphere;
