//! Lesson 06, z-fail with caps: counting behind the surface, the caps that
//! close the volumes, a plan that uses z-fail only where it must, and how
//! far to extrude under a finite far plane.

pub mod caps;
pub mod plan;
pub mod reach;
