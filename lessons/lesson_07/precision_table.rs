//! The depth-precision study's outputs (lesson 07): a CSV of every
//! distance, the chapter's table, and a picture of the resolve grids.

use super::infinite_far::MAPPINGS;
use super::precision_study::{distances, gaps, model_cpu, PrecisionRow, FORMATS};

fn fmt_gap(g: Option<f64>) -> String {
    g.map_or_else(|| "none".into(), |g| format!("{g:.1e}"))
}

/// `format,mapping,near,far,distance,gpu_min_gap,cpu_min_gap` per distance.
pub fn csv(rows: &[PrecisionRow]) -> String {
    let mut s = String::from("format,mapping,near,far,distance,gpu_min_gap,cpu_min_gap\n");
    for r in rows {
        for (i, d) in r.distances.iter().enumerate() {
            let gpu = r
                .gpu
                .as_ref()
                .map_or_else(|| "n/a".into(), |g| fmt_gap(g[i]));
            s += &format!(
                "{},{},{:e},{:e},{:e},{},{}\n",
                r.format.name(),
                r.mapping.name(),
                r.near,
                r.far,
                d,
                gpu,
                fmt_gap(r.cpu[i])
            );
        }
    }
    s
}

/// The chapter's table: the smallest resolvable Δd/d at √(near·far) and at
/// far/2, GPU-measured and (in brackets) CPU-modelled.
pub fn markdown(rows: &[PrecisionRow]) -> String {
    let mut s = String::from("| far/near | format | mapping | Δd/d at √(n·f): GPU (CPU) | Δd/d at f/2: GPU (CPU) |\n|---|---|---|---|---|\n");
    for r in rows {
        let n = r.distances.len();
        let cell = |i: usize| {
            let gpu = r
                .gpu
                .as_ref()
                .map_or_else(|| "n/a".into(), |g| fmt_gap(g[i]));
            format!("{gpu} ({})", fmt_gap(r.cpu[i]))
        };
        s += &format!(
            "| {:.0e} | {} | {} | {} | {} |\n",
            r.far / r.near,
            r.format.name(),
            r.mapping.name(),
            cell(n - 2),
            cell(n - 1)
        );
    }
    s
}

/// The resolve grids side by side (white: the near quad won), one tile per
/// configuration, `scale`× enlarged: columns are gaps, rows distances.
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
                cpu_grid = model_cpu(r.format, r.mapping, r.near, r.far);
                &cpu_grid
            }
        };
        for (y, line) in grid.iter().enumerate() {
            for (x, &ok) in line.iter().enumerate() {
                for dy in 0..scale {
                    for dx in 0..scale {
                        img.put_pixel(
                            ox + x as u32 * scale + dx,
                            oy + y as u32 * scale + dy,
                            image::Luma([if ok { 255 } else { 0 }]),
                        );
                    }
                }
            }
        }
    }
    img
}
