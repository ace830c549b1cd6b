//! Step 4 of a window's frame: the overlay built for the variant shown
//! (its cost, error, view, knobs and counters), tessellated for the
//! present pass, with what the reader clicked.

use super::live::Level;
use super::overlay::{self, Panel, ShownError};
use super::present::Overlay;
use super::views;
use super::App;
use crate::run::instruments::Instruments;
use crate::run::lesson::variant_doc;
use crate::run::view::View;

/// The overlay of one frame, and what came with it.
pub(super) struct Built {
    /// Tessellated, for the present pass.
    pub overlay: Overlay,
    /// What the reader asked for, for the next frame.
    pub actions: overlay::Actions,
    /// The error figure shown, for the log.
    pub shown: Option<ShownError>,
    /// The panel's rectangle in pixels, for the log.
    pub rect_px: Option<[f32; 4]>,
}

impl<L: Instruments> App<L> {
    /// Step 4: the overlay: the panel for `variant` (its doc, cost, error,
    /// view's note, knobs and counters) over the buffer view's picture.
    pub(super) fn build_overlay(&mut self, variant: L::Variant) -> Built {
        let r = self.running.as_mut().expect("checked by redraw");
        let s = &mut self.state;
        let ctx = r.egui.egui_ctx().clone();
        let input = r.egui.take_egui_input(&r.window);
        let knobs = r.lesson.knobs(variant);
        let shown = s.answer.as_ref().map(|a| ShownError {
            error: a.error.clone(),
            level: a.level,
            stale: a.stamp != s.stamp,
            latency_s: s.answer_latency,
        });
        let picture = match s.view {
            View::Buffer => s.buffer.as_ref(),
            _ => None,
        };
        let now_stamp = (s.stamp.scene_gen, s.stamp.image_gen);
        let titled = |title: &str, stamp| match stamp == now_stamp {
            true => title.to_string(),
            false => format!("{title} (of an earlier view; updating)"),
        };
        let view_note = match s.view {
            View::Frame => None,
            View::Visibility => Some("white lit, black shadowed (light 0)".to_string()),
            View::Diff if r.live.is_none() => {
                Some("no diff: the live reference is off".to_string())
            }
            View::Diff => Some(match &s.diff {
                Some((title, stamp)) => titled(title, *stamp),
                None => "computing…".to_string(),
            }),
            View::Dv if r.live.is_none() => Some("no dv: the live reference is off".to_string()),
            View::Dv => Some(match &s.diff {
                Some((title, stamp)) => titled(&dv_title(title), *stamp),
                None => "computing…".to_string(),
            }),
            View::Buffer => match picture {
                Some(p) => Some(titled(&p.title, p.stamp)),
                None => s.buffer_note.clone().or(Some("computing…".to_string())),
            },
        };
        let doc = variant_doc(variant);
        let counters = r.lesson.counters(variant).to_report();
        let adapter = format!("{} ({})", r.gpu.adapter_name(), r.gpu.backend_name());
        if self.adapter_line.is_empty() {
            self.adapter_line = adapter.clone();
        }
        let mut actions = overlay::Actions::default();
        let out = ctx.run_ui(input, |ui| {
            let ctx = ui.ctx().clone();
            if let Some(p) = picture {
                views::paint_behind(&ctx, p, ctx.content_rect());
            }
            if s.show_overlay {
                let panel = Panel {
                    lesson: L::NAME,
                    adapter: &adapter,
                    variants: &s.variants,
                    current: s.current,
                    doc: &doc,
                    cost: &s.cost,
                    error: shown.as_ref(),
                    no_reference: r.live.is_none(),
                    view: s.view,
                    view_note: view_note.as_deref(),
                    knobs: &knobs,
                    settings_line: s.settings_line.as_deref(),
                    lights: r.scene.scene.lights.len(),
                    counters: &counters,
                };
                actions = overlay::show(&ctx, &panel);
            }
        });
        r.egui
            .handle_platform_output(&r.window, out.platform_output);
        let out_ppp = out.pixels_per_point;
        let primitives = ctx.tessellate(out.shapes, out.pixels_per_point);
        let overlay = Overlay {
            primitives,
            textures: out.textures_delta,
            pixels_per_point: out.pixels_per_point,
        };

        let rect_px = actions.rect.map(|r| {
            let ppp = out_ppp;
            [r.min.x * ppp, r.min.y * ppp, r.max.x * ppp, r.max.y * ppp]
        });
        Built {
            overlay,
            actions,
            shown,
            rect_px,
        }
    }
}

/// What the diff image shows, in one line.
pub(super) fn diff_title(a: &super::live::Answer) -> String {
    let level = match a.level {
        Level::Coarse => "coarse estimate",
        Level::Full => "every pixel",
    };
    format!("diff against the exact reference, light 0 ({level}): red false shadow, green false lit, gray agree, near black not a receiver")
}

/// What the dv image shows, in one line, at the diff's `level` (read from
/// its title).
fn dv_title(diff_title: &str) -> String {
    let level = match diff_title.contains("coarse") {
        true => "coarse estimate",
        false => "every pixel",
    };
    format!("signed error V − V_ref, light 0 ({level}): blue darker than exact, red lighter, white agree, dark gray not a receiver")
}
