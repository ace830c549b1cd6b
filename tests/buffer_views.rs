//! The "buffer" view of every lesson (`Instruments::buffer_view`), through the
//! `<variant>_buffer.png` the headless runner writes: it exists, has the
//! size its kind gives it, is not one flat colour, and shows what it says.
//!
//! - lessons 01–03, the shadow map: square, the map's texels; lesson 01's
//!   is the same picture as its `_depth_map.png`, unwritten texels blue;
//! - lesson 04, the cube map as a cross: 4:3, black outside the cross, the
//!   same depths as its `_cube_map.png`;
//! - lessons 05–08, the stencil count of the last light: the frame's size;
//!   lessons 05 and 06: non-zero where the reference shadows, 0 where it lights;
//! - lesson 09, the cascade each pixel samples: several cascade colours.
//!
//! Run it on GL too: `WGPU_BACKEND=gl cargo test --test buffer_views`.

use std::path::Path;

use image::RgbaImage;

const SIZE: [&str; 6] = ["--width", "320", "--height", "180", "--frames", "1"];

/// Runs `bin` headless on `variant` and returns its buffer view and the run.
fn buffer_of(bin: &str, test: &str, variant: &str) -> Option<(RgbaImage, support::LessonRun)> {
    let args = [&SIZE[..], &["--variant", variant]].concat();
    let run = support::run_lesson(bin, test, &args)?;
    let path = run.out.join(format!("{variant}_buffer.png"));
    assert!(path.is_file(), "{test}: no {}", path.display());
    let img = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8();
    let first = *img.get_pixel(0, 0);
    assert!(
        img.pixels().any(|p| *p != first),
        "{test}: {} is one flat colour",
        path.display()
    );
    Some((img, run))
}

/// The frame's size: the stencil count and the cascade picture.
fn assert_frame_sized(img: &RgbaImage, test: &str) {
    assert_eq!(img.dimensions(), (320, 180), "{test}: not the frame's size");
}

/// Texels no caster wrote, in a shadow map's view (lesson_01 shadow_map.rs).
const UNWRITTEN: [u8; 4] = [40, 70, 170, 255];

/// A shadow map's view: `size`², grey where written (many levels: a
/// depth range, not one value), blue where not; returns the written share.
fn check_shadow_map(img: &RgbaImage, size: u32, test: &str) -> f64 {
    assert_eq!(img.dimensions(), (size, size), "{test}: not the map's size");
    let mut levels = std::collections::BTreeSet::new();
    let mut written = 0usize;
    for p in img.pixels() {
        if p.0 == UNWRITTEN {
            continue;
        }
        let [r, g, b, a] = p.0;
        assert!(
            r == g && g == b && a == 255,
            "{test}: texel {p:?} neither grey nor blue"
        );
        levels.insert(r);
        written += 1;
    }
    assert!(
        levels.len() > 50,
        "{test}: the stored depths show as {} grey levels: not a normalised depth range",
        levels.len()
    );
    let share = written as f64 / img.pixels().len() as f64;
    assert!(
        (0.05..0.99).contains(&share),
        "{test}: {:.1} % of the texels written: the casters and the empty map around them should both show",
        100.0 * share
    );
    share
}

#[test]
fn lesson_01_buffer_is_the_variants_shadow_map() {
    let test = "buffer_view_01";
    let Some((img, run)) = buffer_of(env!("CARGO_BIN_EXE_lesson_01"), test, "res_512") else {
        return;
    };
    check_shadow_map(&img, 512, test);
    // The same picture as write_extras' depth map: grey levels equal,
    // white there exactly where blue here.
    let map = image::open(run.out.join("res_512_depth_map.png"))
        .unwrap()
        .to_luma8();
    assert_eq!(map.dimensions(), img.dimensions());
    let differ = map
        .pixels()
        .zip(img.pixels())
        .filter(|(m, b)| match b.0 {
            UNWRITTEN => m.0[0] != 255,
            [v, ..] => m.0[0] != v,
        })
        .count();
    assert_eq!(
        differ, 0,
        "{test}: {differ} texels differ from res_512_depth_map.png"
    );
}

#[test]
fn lesson_02_buffer_is_a_shadow_map() {
    let test = "buffer_view_02";
    if let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_02"), test, "slope_hw") {
        check_shadow_map(&img, 1024, test);
    }
}

#[test]
fn lesson_03_buffer_is_a_shadow_map() {
    let test = "buffer_view_03";
    if let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_03"), test, "pcf_3x3") {
        check_shadow_map(&img, 1024, test);
    }
}

#[test]
fn lesson_10_buffer_is_a_shadow_map() {
    let test = "buffer_10";
    if let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_10"), test, "pcss") {
        check_shadow_map(&img, 1024, test);
    }
}

#[test]
fn lesson_04_buffer_is_the_cube_map_as_a_cross() {
    let test = "buffer_view_04";
    let Some((img, run)) = buffer_of(env!("CARGO_BIN_EXE_lesson_04"), test, "linear_1024") else {
        return;
    };
    let (w, h) = img.dimensions();
    assert_eq!(w * 3, h * 4, "{test}: a cross is 4 faces wide, 3 high");
    let face = w / 4;
    // Cells (column, row) of the cross: +Y; -X +Z +X -Z; -Y.
    let in_cross = |x: u32, y: u32| match (x / face, y / face) {
        (1, _) => true,
        (_, r) => r == 1,
    };
    let (mut grey, mut white) = (0, 0);
    for (x, y, p) in img.enumerate_pixels() {
        let v = p.0[0];
        if !in_cross(x, y) {
            assert_eq!(v, 0, "{test}: ({x}, {y}) outside the cross is not black");
        } else {
            assert!(v > 0, "{test}: ({x}, {y}) inside the cross is black");
            grey += usize::from(v < 255);
            white += usize::from(v == 255);
        }
    }
    assert!(
        grey > 1000 && white > 1000,
        "{test}: {grey} written, {white} unwritten pixels"
    );
    // The same depths as write_extras' cross (128 px a face): compare
    // each of its pixels with the view's at the same place.
    let cross = image::open(run.out.join("linear_1024_cube_map.png"))
        .unwrap()
        .to_luma8();
    let k = face / 128;
    let (mut near, mut n) = (0usize, 0usize);
    for (x, y, p) in cross.enumerate_pixels() {
        let v = img.get_pixel(x * k, y * k).0[0];
        n += 1;
        near += usize::from(p.0[0].abs_diff(v) <= 8);
    }
    let pct = 100.0 * near as f64 / n as f64;
    eprintln!("{test}: {pct:.2} % of linear_1024_cube_map.png's pixels match");
    assert!(
        pct > 97.0,
        "{test}: only {pct:.1} % of the pixels match linear_1024_cube_map.png"
    );
}

/// Count 0 in the stencil view is black (lesson_05 count_view.rs).
fn count_is_zero(p: &image::Rgba<u8>) -> bool {
    p.0 == [0, 0, 0, 255]
}

/// The colours of counts 1 and "below 0" (lesson_05 count_view.rs).
const COUNT_1: [u8; 4] = [220, 50, 40, 255];
const BELOW_ZERO: [u8; 4] = [230, 60, 230, 255];

/// For the surfaces the reference sees: the share where "count ≠ 0"
/// agrees with "the reference shadows light `light`", and the shares of
/// count 1 and of "below 0" among the non-zero counts.
fn agreement_with_reference(img: &RgbaImage, out: &Path, light: usize) -> [f64; 3] {
    let (ids, vis, w, h) =
        support::read_visibility(&out.join(format!("reference_visibility_l{light}.png")));
    assert_eq!((w, h), img.dimensions());
    let (mut agree, mut n, mut counted, mut ones, mut below) = (0, 0, 0, 0, 0);
    for (i, p) in img.pixels().enumerate() {
        if ids[i] == 0 {
            continue; // no surface
        }
        n += 1;
        let shadowed = vis[i] < 0.5;
        agree += usize::from(shadowed != count_is_zero(p));
        if !count_is_zero(p) {
            counted += 1;
            ones += usize::from(p.0 == COUNT_1);
            below += usize::from(p.0 == BELOW_ZERO);
        }
    }
    assert!(n > 10_000, "the reference sees {n} surface pixels");
    let pct = |k: usize, of: usize| 100.0 * k as f64 / of.max(1) as f64;
    [pct(agree, n), pct(ones, counted), pct(below, counted)]
}

/// A stencil view of light `light` agrees with the reference on > 95 %
/// of the surfaces.
fn check_count_against_reference(bin: &str, test: &str, variant: &str, light: usize) {
    let Some((img, run)) = buffer_of(bin, test, variant) else {
        return;
    };
    assert_frame_sized(&img, test);
    let [pct, ones, below] = agreement_with_reference(&img, &run.out, light);
    eprintln!(
        "{test}: the count agrees with reference_visibility_l{light} on {pct:.2} %; of the non-zero counts, {ones:.1} % are 1, {below:.2} % below 0"
    );
    assert!(
        pct > 95.0,
        "{test}: the count is 0 exactly where reference_visibility_l{light} lights on only {pct:.2} % of the surfaces"
    );
    // The default scenes' shadows are mostly one volume deep, none below 0
    // (the eye is in no volume): the counts are read as numbers, not bits.
    assert!(
        ones > 50.0 && below < 0.5,
        "{test}: of the non-zero counts {ones:.1} % are 1 and {below:.2} % below 0"
    );
}

#[test]
fn lesson_05_buffer_counts_where_the_reference_shadows() {
    // Two lights: the stencil holds light 1's count.
    let bin = env!("CARGO_BIN_EXE_lesson_05");
    check_count_against_reference(bin, "buffer_view_05", "zpass_quads", 1);
}

#[test]
fn lesson_06_buffer_counts_where_the_reference_shadows() {
    let bin = env!("CARGO_BIN_EXE_lesson_06");
    check_count_against_reference(bin, "buffer_view_06", "zfail_quads", 1);
}

#[test]
fn lesson_07_buffer_is_a_stencil_count() {
    let test = "buffer_view_07";
    if let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_07"), test, "clamp") {
        assert_frame_sized(&img, test);
    }
}

#[test]
fn lesson_08_buffer_is_a_stencil_count() {
    let test = "buffer_view_08";
    if let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_08"), test, "unbounded") {
        assert_frame_sized(&img, test);
    }
}

#[test]
fn lesson_09_buffer_shows_several_cascades() {
    let test = "buffer_view_09";
    let Some((img, _)) = buffer_of(env!("CARGO_BIN_EXE_lesson_09"), test, "k4") else {
        return;
    };
    assert_frame_sized(&img, test);
    // The tints of csm.wgsl (red, green, blue, yellow), shaded: tell them
    // apart by which channels lead.
    let mut seen = [0usize; 4];
    for p in img.pixels() {
        let [r, g, b, _] = p.0.map(u32::from);
        if r + g + b < 60 {
            continue; // background, or too dark to tell
        }
        let class = if r > 2 * b && g > 2 * b && r.abs_diff(g) * 5 < r {
            3
        } else if r > g && r > b {
            0
        } else if g > r && g > b {
            1
        } else {
            2
        };
        seen[class] += 1;
    }
    eprintln!("{test}: pixels per cascade colour {seen:?}");
    let shown = seen.iter().filter(|&&n| n > 500).count();
    assert!(
        shown >= 3,
        "{test}: cascade colours seen {seen:?} (red, green, blue, yellow)"
    );
}
