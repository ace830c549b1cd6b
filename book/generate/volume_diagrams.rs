//! Chapter 05's pictures of shadow volumes, drawn from lesson 05's own
//! code (`adjacency`, `silhouette`, `extrusion`) on the cube of
//! `scenes/lesson_05.toml`: the silhouette, the volume's sides and caps,
//! the z-pass count along two view rays, the stencil counts of a frame and
//! the extrusion to w = 0. Every number a picture shows is computed here.
//! This file lists them and writes them.
//!
//! One file a picture under `volume_diagrams/`: [`silhouette`],
//! [`sides_and_caps`], [`zpass_count`], [`stencil_counts`], [`w_zero`] and
//! [`passes`]; what they share: [`caster`] (the cube and its camera) and
//! [`draw`] (colours, fitting, labels).

mod caster;
mod draw;
#[cfg(test)]
mod independent;
mod passes;
mod sides_and_caps;
mod silhouette;
mod stencil_counts;
mod w_zero;
mod zpass_count;

use std::path::Path;

use anyhow::Result;
use common::scene::Scene;

use caster::Caster;
use passes::passes;
use sides_and_caps::sides_and_caps;
use silhouette::silhouette;
use stencil_counts::stencil_counts;
use w_zero::w_zero;
use zpass_count::zpass_count;

/// Writes chapter 05's diagrams into `dir` and returns the names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    crate::diagrams::write_svgs(dir, render(root)?)
}

/// Chapter 05's diagrams, as (file name, SVG text).
fn render(root: &Path) -> Result<[(&'static str, String); 6]> {
    let scene = Scene::load(&root.join("scenes/lesson_05.toml"))?;
    let caster = Caster::from_scene(&scene)?;
    Ok([
        ("volume_silhouette.svg", silhouette(&caster)),
        ("volume_sides_caps.svg", sides_and_caps(&caster)),
        ("volume_zpass_count.svg", zpass_count()?),
        ("volume_stencil_counts.svg", stencil_counts(&scene)?),
        ("volume_w_zero.svg", w_zero(&scene, &caster)?),
        ("volume_passes.svg", passes()),
    ])
}

#[cfg(test)]
mod tests {
    use crate::diagrams::svg::tests::assert_texts_fit;

    /// Chapter 05's diagrams: their texts inside the canvas and apart.
    #[test]
    fn texts_inside_the_canvas_and_apart() {
        for (name, svg) in super::render(&crate::repo_root()).unwrap() {
            assert_texts_fit(name, &svg);
        }
    }
}
