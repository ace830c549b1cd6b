//! Chapter 10's pictures of PCSS, drawn from lesson 10's own scene
//! (`scenes/lesson_10.toml`) and geometry (`LightGeometry`, the light's
//! matrix): the similar triangles of the penumbra's width, and the blocker
//! search's footprint on the shadow map. Every number a picture shows is
//! computed here.
//!
//! The penumbra's formula and the search's taps live in WGSL only
//! (`shaders/lesson_10/soft.wgsl`: `filter_radius`, `vogel`): the first
//! picture constructs the triangles by intersecting rays instead, and the
//! second restates those two small functions (`filter_radius`, `vogel` in
//! [`blocker_search`]), checked against the geometric footprint it draws
//! beside them. Both show the same floor point p, and print its distances
//! as the text defines them: from the light, along its axis. Each
//! picture's module tests its central fact against an independent
//! computation (the printed distances and the footprint's radius; the
//! search disk as the emitter seen from p). This file lists the pictures
//! and writes them; one file a picture under `soft_diagrams/`, and
//! [`setup`], the scene and the point they share.

mod blocker_search;
mod setup;
mod similar_triangles;

use std::path::Path;

use anyhow::Result;
use common::scene::Scene;

use blocker_search::blocker_search;
use setup::Setup;
use similar_triangles::similar_triangles;

/// Writes chapter 10's diagrams into `dir` and returns the names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    crate::diagrams::write_svgs(dir, render(root)?)
}

/// Chapter 10's diagrams, as (file name, SVG text).
fn render(root: &Path) -> Result<[(&'static str, String); 2]> {
    let scene = Scene::load(&root.join("scenes/lesson_10.toml"))?;
    let setup = Setup::from_scene(&scene)?;
    Ok([
        ("soft_similar_triangles.svg", similar_triangles(&setup)),
        ("soft_blocker_search.svg", blocker_search(&scene, &setup)?),
    ])
}

#[cfg(test)]
mod tests {
    use crate::diagrams::svg::tests::assert_texts_fit;

    /// Chapter 10's diagrams: their texts inside the canvas and apart.
    #[test]
    fn texts_inside_the_canvas_and_apart() {
        for (name, svg) in super::render(&crate::repo_root()).unwrap() {
            assert_texts_fit(name, &svg);
        }
    }
}
