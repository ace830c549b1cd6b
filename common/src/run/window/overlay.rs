//! The overlay (egui): which lesson and variant run, on which adapter,
//! what a frame costs, how wrong the variant is against the exact
//! reference, the view, the technique's knobs, and the keys.

use std::collections::BTreeMap;

use egui::{Color32, RichText};

use crate::reference::metrics::ErrorStats;
use crate::run::knobs::{Knob, KnobRange};
use crate::run::view::View;
use crate::run::window::live::{Level, COARSE};

/// Every key, drag and view of the window, as the overlay's help lists them.
pub const KEYS: &[(&str, &str)] = &[
    ("drag (left button)", "orbit the camera around its target"),
    ("scroll", "move the camera closer or further"),
    ("arrows", "move the first light (directional: turn it)"),
    (
        "PageUp / PageDown",
        "move a point or spot light up and down",
    ),
    ("V or Space / Shift+V", "next / previous variant"),
    (
        "1 2 3 4 5, Tab",
        "view: frame, visibility, diff, buffer, dv",
    ),
    ("K", "print the command line that reproduces this, headless"),
    ("H", "hide or show this overlay"),
    ("Escape", "quit"),
];

/// What the web build's overlay says where the adapter offers no
/// timestamps.
pub const WEB_NO_TIMESTAMPS: &str = "no GPU time: this browser's adapter offers no timestamp-query (the desktop lesson times the GPU)";

/// The figure the overlay shows, and what it was computed for.
pub struct ShownError {
    pub error: ErrorStats,
    pub level: Level,
    /// It is of another view, variant or knob setting than the one shown.
    pub stale: bool,
    /// Seconds since the view changed until this figure came, for the
    /// current view (`None` while stale).
    pub latency_s: Option<f64>,
}

/// What a frame cost, in milliseconds (the report's `timing_ms` keys).
#[derive(Clone, Default)]
pub struct Cost {
    pub ms: BTreeMap<String, f64>,
    /// Frames per second of the window, over the last second.
    pub fps: f64,
    /// The GPU's times of the last frames timed ([`GPU_FRAMES`] at most),
    /// oldest first: each frame's passes and `total`.
    pub gpu: std::collections::VecDeque<BTreeMap<String, f64>>,
    /// In a web page: how many frames late the newest GPU times were read,
    /// and the step the browser rounds timestamps to (ns); `None` where
    /// the adapter has no timestamps.
    pub late: Option<(u64, u64)>,
}

/// How many frames' GPU times the overlay's median and spread are over.
pub const GPU_FRAMES: usize = 30;

impl Cost {
    /// Adds a frame's GPU times (the passes and `total` of `ms`).
    pub fn push_gpu(&mut self, ms: &BTreeMap<String, f64>) {
        let gpu = ms
            .iter()
            .filter(|(k, _)| !k.starts_with("cpu_") && k.as_str() != crate::measure::timing::FRAME)
            .map(|(k, v)| (k.clone(), *v))
            .collect::<BTreeMap<_, _>>();
        if !gpu.contains_key(crate::measure::timing::TOTAL) {
            return;
        }
        self.gpu.push_back(gpu);
        while self.gpu.len() > GPU_FRAMES {
            self.gpu.pop_front();
        }
    }

    /// `key`'s median and interquartile range over the frames kept:
    /// `[q25, median, q75]`, or `None` before any.
    pub fn gpu_spread(&self, key: &str) -> Option<[f64; 3]> {
        let v: Vec<f64> = self
            .gpu
            .iter()
            .map(|f| f.get(key).copied().unwrap_or(0.0))
            .collect();
        if v.is_empty() {
            return None;
        }
        let q = |p| crate::measure::timing::quantile(&v, p);
        Some([q(0.25), q(0.5), q(0.75)])
    }
}

/// Everything the overlay shows this frame.
pub struct Panel<'a> {
    pub lesson: &'a str,
    pub adapter: &'a str,
    pub variants: &'a [String],
    pub current: usize,
    pub doc: &'a str,
    pub cost: &'a Cost,
    pub error: Option<&'a ShownError>,
    /// The live reference is off (`--no-live-reference`).
    pub no_reference: bool,
    pub view: View,
    /// The image view's title (diff, buffer), or why it has none.
    pub view_note: Option<&'a str>,
    pub knobs: &'a [Knob],
    pub settings_line: Option<&'a str>,
    pub lights: usize,
    /// The lesson's counters for the variant shown (the report's).
    pub counters: &'a BTreeMap<String, u64>,
}

/// What the user asked for through the overlay's widgets.
#[derive(Default)]
pub struct Actions {
    pub variant: Option<usize>,
    pub view: Option<View>,
    pub knobs: Vec<(&'static str, f64)>,
    pub print_settings: bool,
    /// Where the overlay's panel is, in points.
    pub rect: Option<egui::Rect>,
}

/// Builds the overlay for this frame.
pub fn show(ctx: &egui::Context, p: &Panel) -> Actions {
    let mut act = Actions::default();
    let frame = egui::Frame::window(&ctx.global_style()).fill(Color32::from_black_alpha(235));
    let shown = egui::Window::new(p.lesson)
        .frame(frame)
        .anchor(egui::Align2::LEFT_TOP, [8.0, 8.0])
        .resizable(false)
        .default_width(330.0)
        .show(ctx, |ui| {
            ui.label(RichText::new(format!("adapter: {}", p.adapter)).small());
            variant_row(ui, p, &mut act);
            ui.separator();
            cost_rows(ui, p.cost);
            ui.separator();
            error_rows(ui, p);
            counter_rows(ui, p.counters);
            ui.separator();
            view_row(ui, p, &mut act);
            knob_rows(ui, p.knobs, &mut act);
            if ui.button("print settings (K)").clicked() {
                act.print_settings = true;
            }
            if let Some(line) = p.settings_line {
                ui.label(RichText::new(line).small().monospace());
            }
            egui::CollapsingHeader::new("keys")
                .default_open(false)
                .show(ui, |ui| {
                    egui::Grid::new("keys").show(ui, |ui| {
                        // A page has no window to close.
                        let web = cfg!(target_arch = "wasm32");
                        for (k, what) in KEYS.iter().filter(|(k, _)| !(web && *k == "Escape")) {
                            ui.label(RichText::new(*k).monospace());
                            ui.label(*what);
                            ui.end_row();
                        }
                    });
                });
        });
    act.rect = shown.map(|r| r.response.rect);
    act
}

fn variant_row(ui: &mut egui::Ui, p: &Panel, act: &mut Actions) {
    ui.horizontal(|ui| {
        ui.label("variant");
        let mut chosen = p.current;
        egui::ComboBox::from_id_salt("variant")
            .selected_text(&p.variants[p.current])
            .show_ui(ui, |ui| {
                for (i, v) in p.variants.iter().enumerate() {
                    ui.selectable_value(&mut chosen, i, v);
                }
            });
        ui.label(format!("{}/{}", p.current + 1, p.variants.len()));
        if chosen != p.current {
            act.variant = Some(chosen);
        }
    });
    if !p.doc.is_empty() {
        ui.label(RichText::new(p.doc).italics());
    }
}

fn cost_rows(ui: &mut egui::Ui, c: &Cost) {
    let ms = |k: &str| c.ms.get(k).copied();
    let fmt = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{v:.2} ms"));
    let gpu = match c.gpu_spread(crate::measure::timing::TOTAL) {
        Some([lo, mid, hi]) => format!("{mid:.2} ms [{lo:.2}–{hi:.2}]"),
        None => "–".to_string(),
    };
    // A frame read back later is not waited for: no wall-clock frame time.
    let waited = c.late.is_none() && !cfg!(target_arch = "wasm32");
    if waited {
        ui.label(format!(
            "frame {}   GPU {gpu}   CPU {}   {:.1} fps",
            fmt(ms("frame")),
            fmt(ms("cpu_total")),
            c.fps
        ));
    } else {
        ui.label(format!(
            "GPU {gpu}   CPU {}   {:.1} fps",
            fmt(ms("cpu_total")),
            c.fps
        ));
    }
    let passes: Vec<String> = (c.gpu.back().into_iter().flatten())
        .filter(|(k, _)| k.as_str() != crate::measure::timing::TOTAL)
        .filter_map(|(k, _)| Some(format!("{k} {:.2}", c.gpu_spread(k)?[1])))
        .collect();
    if !passes.is_empty() {
        ui.label(RichText::new(format!("passes (ms): {}", passes.join(", "))).small());
    }
    let n = c.gpu.len();
    let note = match c.late {
        Some((late, quantum_ns)) => {
            let rounded = match quantum_ns >= 1000 {
                true => format!(
                    "; the browser rounds timestamps to {:.0} µs",
                    quantum_ns as f64 / 1e3
                ),
                false => String::new(),
            };
            let frames = if late == 1 { "frame" } else { "frames" };
            format!("GPU: median [quartiles] of the last {n} frames timed, read {late} {frames} later{rounded}")
        }
        None if !waited => WEB_NO_TIMESTAMPS.to_string(),
        None => format!("GPU: median [quartiles] of the last {n} frames"),
    };
    ui.label(RichText::new(note).small());
}

fn counter_rows(ui: &mut egui::Ui, counters: &BTreeMap<String, u64>) {
    ui.separator();
    let text = match counters.is_empty() {
        // A page's counts come back a frame or more after they are drawn.
        true => "counters: none yet".to_string(),
        false => {
            let all: Vec<String> = counters.iter().map(|(k, v)| format!("{k} {v}")).collect();
            format!(
                "counters (on the variant's first frames): {}",
                all.join(", ")
            )
        }
    };
    ui.label(RichText::new(text).small());
}

fn error_rows(ui: &mut egui::Ui, p: &Panel) {
    if p.no_reference {
        ui.label("error: the live reference is off (--no-live-reference)");
        return;
    }
    let Some(e) = p.error else {
        ui.label("error against the exact reference: computing…");
        return;
    };
    let s = &e.error;
    let red = Color32::from_rgb(255, 90, 90);
    let green = Color32::from_rgb(90, 220, 90);
    ui.horizontal(|ui| {
        ui.label(RichText::new(format!("misclassified {:.3} %", s.misclassified_pct)).strong());
        ui.label(RichText::new(format!("false shadow {:.3} %", s.false_shadow_pct)).color(red));
        ui.label(RichText::new(format!("false lit {:.3} %", s.false_lit_pct)).color(green));
    });
    // An area light's soft shadow: the error inside its penumbra.
    if let Some(soft) = &s.soft {
        ui.label(RichText::new(format!(
            "penumbra |ΔV| {:.3} %   bleeding {:.3} % of the umbra",
            100.0 * soft.penumbra_mean_abs,
            soft.light_bleeding_pct
        )));
    }
    let lights = if p.lights > 1 {
        format!(", {} lights", p.lights)
    } else {
        String::new()
    };
    let status = match (e.stale, e.level) {
        (true, _) => "recomputing for this view… (the figure above is the last one)".to_string(),
        (false, Level::Coarse) => format!(
            "estimate from 1 ray in {} pixels; the full reference follows",
            COARSE * COARSE
        ),
        (false, Level::Full) => format!(
            "exact reference, every pixel ({} receivers{lights})",
            s.receiver_pixels
        ),
    };
    ui.label(RichText::new(status).small());
    if let (false, Some(t)) = (e.stale, e.latency_s) {
        ui.label(RichText::new(format!("came {t:.2} s after the view changed")).small());
    }
}

fn view_row(ui: &mut egui::Ui, p: &Panel, act: &mut Actions) {
    ui.horizontal(|ui| {
        ui.label("view");
        for v in View::ALL {
            let text = format!("{} {}", v.key(), v.label());
            if ui.selectable_label(p.view == v, text).clicked() && p.view != v {
                act.view = Some(v);
            }
        }
    });
    if let Some(note) = p.view_note {
        ui.label(RichText::new(note).small());
    }
}

fn knob_rows(ui: &mut egui::Ui, knobs: &[Knob], act: &mut Actions) {
    if knobs.is_empty() {
        return;
    }
    ui.separator();
    ui.label("knobs");
    for k in knobs {
        let mut v = k.value;
        let changed = match k.range {
            KnobRange::Float { min, max, log } => ui
                .add(
                    egui::Slider::new(&mut v, min..=max)
                        .logarithmic(log)
                        .text(k.name),
                )
                .changed(),
            KnobRange::Int { min, max } => {
                let mut i = v as i64;
                let c = ui
                    .add(egui::Slider::new(&mut i, min..=max).text(k.name))
                    .changed();
                v = i as f64;
                c
            }
            KnobRange::Toggle => {
                let mut on = v != 0.0;
                let c = ui.checkbox(&mut on, k.name).changed();
                v = if on { 1.0 } else { 0.0 };
                c
            }
        };
        if !k.doc.is_empty() {
            ui.label(RichText::new(k.doc).small());
        }
        if changed && v != k.value {
            act.knobs.push((k.name, v));
        }
    }
}
