//! Lesson 01, the depth map: the shadow map and the pass that fills it.

pub mod shadow_map;

pub mod tally;
