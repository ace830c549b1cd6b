//! Lesson 04, cube-map point shadows: six faces, two ways to store depth,
//! and culling what the light cannot see.

pub mod costs;
pub mod cross;
pub mod cube_map;
pub mod culling;
