//! Lesson 09, cascaded shadow maps: the view frustum split by depth, one
//! fitted, snapped map per slice, all in one depth texture array.

pub mod cascades;

pub mod csm;

pub mod extras;

pub mod setup;
