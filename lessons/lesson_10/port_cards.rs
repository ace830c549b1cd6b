//! The cards of lesson 10's ports ([`common::ports`]): for each renderer,
//! its default shadow filter and the soft options a user turns on, the
//! files and commits each was read at, every constant and formula the port
//! takes from there with its lines (the map's size, the faces its shadow
//! pass draws, its offsets, its kernel), and what the port cannot do here.
//! `tests/port_cards_lesson_10.rs` checks each port ([`super::peers`],
//! `shaders/lesson_10/peers.wgsl`) against its card; the chapter's "where
//! each port departs" table is made from these.
//!
//! One file per renderer ([`filament`], [`bevy`], [`godot`], [`threejs`]).
//! Line numbers were read in the files' stored text at the commits named.

use common::ports::PortCard;

mod bevy;
mod filament;
mod godot;
mod threejs;

pub use bevy::*;
pub use filament::*;
pub use godot::*;
pub use threejs::*;

/// Every card of lesson 10, in the variants' order.
pub const CARDS: &[PortCard] = &[
    FILAMENT_PCF,
    FILAMENT_PCSS,
    FILAMENT_EVSM,
    BEVY_GAUSSIAN,
    BEVY_PCSS_OR_PCF,
    GODOT_PCF,
    GODOT_SOFT_LOW,
    THREEJS_PCF,
    THREEJS_PCF_SOFT,
    THREEJS_VSM,
];
