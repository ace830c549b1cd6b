//! The book's conceptual diagrams, drawn as hand-built SVG from the
//! workbook's own code and scenes (issue 9): every number a picture shows
//! is computed from the lesson's functions, not typed in. This file lists
//! them and writes them; chapter 05's are in `volume_diagrams.rs`, chapter
//! 10's in `soft_diagrams.rs`.
//!
//! One file a diagram under `diagrams/`, and what they share:
//! - [`shadow_map_idea`] (the introduction's Figure 0.1), [`acne`] (02),
//!   [`cube_faces`] (04), [`zpass_zfail`] (05 and 06), [`range_sphere`]
//!   (08). Each file's tests read the drawn SVG back and check its central
//!   geometric fact against a computation of their own (ray casting,
//!   an emulated map, marching a ray, the cube-map rule, a sampled sphere),
//!   not the drawing's helpers.
//! - [`svg`]: the SVG canvas they are drawn on.
//! - [`crossings`]: a view ray's count through a 2D shadow volume.

mod acne;
pub(crate) mod crossings;
mod cube_faces;
mod range_sphere;
mod shadow_map_idea;
pub(crate) mod svg;
mod zpass_zfail;

use std::path::Path;

use anyhow::{Context, Result};

/// Writes the diagrams into `dir` and returns the file names written.
pub fn write_all(root: &Path, dir: &Path) -> Result<Vec<String>> {
    write_svgs(dir, render(root)?)
}

/// Writes `(file name, SVG text)` pairs into `dir`; returns the names.
pub(crate) fn write_svgs(
    dir: &Path,
    svgs: impl IntoIterator<Item = (&'static str, String)>,
) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let mut names = Vec::new();
    for (name, svg) in svgs {
        let path = dir.join(name);
        std::fs::write(&path, svg).with_context(|| format!("{}: cannot write", path.display()))?;
        names.push(name.to_string());
    }
    Ok(names)
}

/// The diagrams, as (file name, SVG text).
pub(crate) fn render(root: &Path) -> Result<[(&'static str, String); 5]> {
    Ok([
        ("shadow_map_idea.svg", shadow_map_idea::shadow_map_idea()?),
        ("acne_staircase.svg", acne::acne_staircase(root)?),
        ("zpass_zfail_ray.svg", zpass_zfail::zpass_zfail_ray()?),
        ("cube_faces.svg", cube_faces::cube_faces()?),
        ("range_sphere.svg", range_sphere::range_sphere(root)?),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use svg::tests::assert_texts_fit;

    /// This file's diagrams (chapter 05's and chapter 10's test theirs).
    #[test]
    fn texts_inside_the_canvas_and_apart() {
        for (name, svg) in render(&crate::repo_root()).unwrap() {
            assert_texts_fit(name, &svg);
        }
    }

    /// Every module that draws a diagram (it opens an `Svg`) checks its
    /// central geometric fact in a test of its own: a drawing that looks
    /// right is not yet right.
    #[test]
    fn every_diagram_tests_its_geometry() {
        let root = crate::repo_root().join("book/generate");
        let mut drawn = 0;
        let mut untested = Vec::new();
        for dir in ["diagrams", "volume_diagrams", "soft_diagrams"] {
            for e in std::fs::read_dir(root.join(dir)).unwrap() {
                let p = e.unwrap().path();
                let text = std::fs::read_to_string(&p).unwrap();
                if !text.contains("Svg::new(") {
                    continue;
                }
                drawn += 1;
                if !text.contains("#[test]") {
                    untested.push(p.display().to_string());
                }
            }
        }
        // The 13 diagrams of the book (figures/diagrams/).
        assert!(drawn >= 13, "found {drawn} diagram modules, not 13");
        assert!(
            untested.is_empty(),
            "diagrams without a geometry test: {untested:?}"
        );
    }
}
