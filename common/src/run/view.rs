//! What the window shows: the frame, the variant's visibility, its
//! difference against the exact reference (classified, or the signed
//! visibility error ΔV), or the lesson's own buffer (`--view` picks the
//! first; the window's keys switch).

use clap::ValueEnum;

/// The window's views (keys 1 to 4, Tab cycles, `--view` picks the first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum View {
    /// The shaded frame.
    Frame,
    /// The variant's visibility of light 0: white lit, black shadowed.
    Visibility,
    /// Against the exact reference (light 0): red false shadow, green false
    /// lit, gray where both agree (lighter lit), near black not a receiver.
    Diff,
    /// The signed visibility error against the exact reference (light 0):
    /// blue where the GPU is darker, red where it is lighter, white where
    /// they agree; a soft shadow's penumbra error shows here, not in
    /// [`View::Diff`] (common/src/reference/dv_view.rs).
    Dv,
    /// The lesson's own buffer: the shadow map, the cube map's cross, the
    /// stencil count or the cascades.
    Buffer,
}

impl View {
    pub const ALL: [View; 5] = [
        View::Frame,
        View::Visibility,
        View::Diff,
        View::Buffer,
        View::Dv,
    ];

    /// The key that shows it.
    pub fn key(self) -> char {
        match self {
            View::Frame => '1',
            View::Visibility => '2',
            View::Diff => '3',
            View::Buffer => '4',
            View::Dv => '5',
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            View::Frame => "frame",
            View::Visibility => "visibility",
            View::Diff => "diff",
            View::Dv => "dv",
            View::Buffer => "buffer",
        }
    }

    /// The view after this one (Tab).
    pub fn next(self) -> View {
        let i = View::ALL.iter().position(|&v| v == self).unwrap_or(0);
        View::ALL[(i + 1) % View::ALL.len()]
    }

    /// The view a key shows, if any.
    pub fn of_key(c: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| c == v.key().to_string())
    }
}
