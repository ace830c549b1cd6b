//! Lesson 06, z-fail with caps: counting behind the surface, the caps that
//! close the volumes, and a plan that uses z-fail only where it must.

pub mod caps;
pub mod plan;
