//! What the window shows: the frame, the variant's visibility, its
//! difference against the exact reference, or the lesson's own buffer
//! (`--view` picks the first; the window's keys switch).

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
    /// The lesson's own buffer: the shadow map, the cube map's cross, the
    /// stencil count or the cascades.
    Buffer,
}

impl View {
    pub const ALL: [View; 4] = [View::Frame, View::Visibility, View::Diff, View::Buffer];

    /// The key that shows it.
    pub fn key(self) -> char {
        match self {
            View::Frame => '1',
            View::Visibility => '2',
            View::Diff => '3',
            View::Buffer => '4',
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            View::Frame => "frame",
            View::Visibility => "visibility",
            View::Diff => "diff",
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
