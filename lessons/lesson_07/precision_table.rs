//! The depth-precision study's outputs (lesson 07): a CSV of every
//! distance, the chapter's table, a picture of the resolve grids, and a
//! plot of every row against the analytic curve.

use std::fmt::Write;

use super::infinite_far::{DepthMapping, MAPPINGS};
use super::precision_study::{distances, gaps, model_cpu, DepthFormat, PrecisionRow, FORMATS};

fn fmt_gap(g: Option<f64>) -> String {
    g.map_or_else(|| "none".into(), |g| format!("{g:.1e}"))
}

fn gpu_cell(r: &PrecisionRow, i: usize) -> String {
    r.gpu
        .as_ref()
        .map_or_else(|| "n/a".into(), |g| fmt_gap(g[i]))
}

/// `format,mapping,near,far,distance,gpu_min_gap,cpu_min_gap,analytic_gap,storage`
/// (`storage`: what the format stores on this adapter, which the CPU model
/// and the analytic curve assume).
pub fn csv(rows: &[PrecisionRow]) -> String {
    let mut s = String::from(
        "format,mapping,near,far,distance,gpu_min_gap,cpu_min_gap,analytic_gap,storage\n",
    );
    for r in rows {
        for (i, d) in r.distances.iter().enumerate() {
            let _ = writeln!(
                s,
                "{},{},{:e},{:e},{:e},{},{},{:.1e},{}",
                r.format.name(),
                r.mapping.name(),
                r.near,
                r.far,
                d,
                gpu_cell(r, i),
                fmt_gap(r.cpu[i]),
                r.analytic[i],
                r.storage.name()
            );
        }
    }
    s
}

/// The chapter's table, every configuration: the smallest Δd/d resolved in
/// 95 % of the samples at √(near·far) and at far/2, as GPU-measured, CPU
/// model, and analytic.
pub fn markdown(rows: &[PrecisionRow]) -> String {
    let mut s = String::from(
        "| far/near | format | mapping | at √(n·f): GPU / CPU / analytic | at f/2: GPU / CPU / analytic |\n|---|---|---|---|---|\n",
    );
    for r in rows {
        let n = r.distances.len();
        let cell = |i: usize| {
            format!(
                "{} / {} / {:.1e}",
                gpu_cell(r, i),
                fmt_gap(r.cpu[i]),
                r.analytic[i]
            )
        };
        let _ = writeln!(
            s,
            "| {:.0e} | {} | {} | {} | {} |",
            r.far / r.near,
            short(r.format),
            r.mapping.name(),
            cell(n - 2),
            cell(n - 1)
        );
    }
    s
}

fn short(f: DepthFormat) -> &'static str {
    match f {
        DepthFormat::D24 => "D24",
        DepthFormat::D32F => "D32F",
    }
}

/// The resolve grids side by side (gray: the share of samples resolved),
/// one tile per configuration, `scale`× enlarged: columns are gaps, rows
/// distances.
pub fn grid_image(rows: &[PrecisionRow], scale: u32) -> image::GrayImage {
    let (gw, gh) = (gaps().len() as u32, distances(1.0, 2.0).len() as u32);
    let cols = MAPPINGS.len() as u32 * FORMATS.len() as u32;
    let lines = (rows.len() as u32).div_ceil(cols);
    let (tw, th) = (gw * scale + 4, gh * scale + 4);
    let mut img = image::GrayImage::from_pixel(cols * tw, lines * th, image::Luma([64]));
    for (k, r) in rows.iter().enumerate() {
        let (ox, oy) = ((k as u32 % cols) * tw + 2, (k as u32 / cols) * th + 2);
        let cpu_grid;
        let grid = match &r.grid {
            Some(g) => g,
            None => {
                cpu_grid = model_cpu(r.storage, r.mapping, r.near, r.far);
                &cpu_grid
            }
        };
        for (y, line) in grid.iter().enumerate() {
            for (x, &share) in line.iter().enumerate() {
                for dy in 0..scale {
                    for dx in 0..scale {
                        img.put_pixel(
                            ox + x as u32 * scale + dx,
                            oy + y as u32 * scale + dy,
                            image::Luma([(share * 255.0).round() as u8]),
                        );
                    }
                }
            }
        }
    }
    img
}

const COLORS: [&str; 4] = ["#c0392b", "#2471a3", "#b7950b", "#239b56"];

// ANCHOR: svg_plot
/// Every row as a curve: one panel per far/near, x = distance, y = the
/// smallest Δd/d resolved in 95 % of samples (log-log). Solid: GPU (the
/// CPU model where the format is missing); dotted: the analytic curve.
/// Colour: mapping; thick: D24, thin: D32F. "none" is drawn at the top.
pub fn svg_plot(rows: &[PrecisionRow]) -> String {
    let mut ratios: Vec<f64> = rows.iter().map(|r| r.far / r.near).collect();
    ratios.dedup();
    let (pw, ph, m) = (360.0, 260.0, 48.0);
    let (w, h) = (
        2.0 * (pw + m) + m,
        ratios.len().div_ceil(2) as f64 * (ph + m) + m + 40.0,
    );
    let mut s = format!(
        "<svg xmlns='http://www.w3.org/2000/svg' width='{w}' height='{h}' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n"
    );
    for (p, &ratio) in ratios.iter().enumerate() {
        let (ox, oy) = (m + (p % 2) as f64 * (pw + m), m + (p / 2) as f64 * (ph + m));
        let in_panel: Vec<&PrecisionRow> =
            rows.iter().filter(|r| r.far / r.near == ratio).collect();
        let d = &in_panel[0].distances;
        let (x0, x1) = (d[0].log10(), d.iter().cloned().fold(0.0, f64::max).log10());
        let x = |v: f64| ox + (v.log10() - x0) / (x1 - x0) * pw;
        // y: 1e-9 at the bottom, 1 (and "none") at the top.
        let y = |g: Option<f64>| oy + ph * (1.0 - (g.unwrap_or(1.0).log10() + 9.0) / 9.0);
        let _ = writeln!(
            s,
            "<rect x='{ox}' y='{oy}' width='{pw}' height='{ph}' fill='none' stroke='#888'/>"
        );
        let _ = writeln!(
            s,
            "<text x='{}' y='{}'>far/near = {ratio:.0e} (near = {:.0e})</text>",
            ox + 4.0,
            oy - 6.0,
            in_panel[0].near
        );
        for e in -9..=0 {
            let yy = y(Some(10f64.powi(e)));
            let _ = writeln!(s, "<line x1='{ox}' x2='{}' y1='{yy}' y2='{yy}' stroke='#eee'/><text x='{}' y='{}' text-anchor='end'>1e{e}</text>", ox + pw, ox - 3.0, yy + 4.0);
        }
        for i in [0, d.len() - 1] {
            let _ = writeln!(
                s,
                "<text x='{}' y='{}' text-anchor='middle'>d = {:.0e}</text>",
                x(d[i]),
                oy + ph + 14.0,
                d[i]
            );
        }
        for r in in_panel {
            let color = COLORS[MAPPINGS.iter().position(|&q| q == r.mapping).unwrap_or(0)];
            let width = if r.format == DepthFormat::D24 {
                2.5
            } else {
                1.0
            };
            // Sorted by distance: the two named distances are appended last.
            let mut idx: Vec<usize> = (0..r.distances.len()).collect();
            idx.sort_by(|&a, &b| r.distances[a].total_cmp(&r.distances[b]));
            let line = |val: &dyn Fn(usize) -> Option<f64>| {
                idx.iter()
                    .map(|&i| format!("{:.1},{:.1}", x(r.distances[i]), y(val(i))))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let measured = line(&|i| r.best(i));
            let analytic = line(&|i| Some(r.analytic[i].min(1.0)));
            let _ = writeln!(s, "<polyline points='{measured}' fill='none' stroke='{color}' stroke-width='{width}'/>");
            let _ = writeln!(s, "<polyline points='{analytic}' fill='none' stroke='{color}' stroke-width='{width}' stroke-dasharray='2,3' opacity='0.7'/>");
        }
    }
    let ly = h - 24.0;
    for (k, mp) in MAPPINGS.iter().enumerate() {
        let lx = m + k as f64 * 150.0;
        let _ = writeln!(s, "<line x1='{lx}' x2='{}' y1='{ly}' y2='{ly}' stroke='{}' stroke-width='2.5'/><text x='{}' y='{}'>{}</text>", lx + 20.0, COLORS[k], lx + 24.0, ly + 4.0, name(*mp));
    }
    let _ = writeln!(s, "<text x='{m}' y='{}'>thick: Depth24PlusStencil8, thin: Depth32FloatStencil8; solid: measured (95 % of {} samples), dotted: analytic; y: smallest Δd/d resolved</text>", ly + 18.0, super::precision_study::SAMPLES);
    s + "</svg>\n"
}
// ANCHOR_END: svg_plot

fn name(m: DepthMapping) -> &'static str {
    m.name()
}
