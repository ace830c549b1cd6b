//! The vocabulary of the mutations: extreme numbers, the keys and values
//! of the scene and spec formats, OBJ tags and arguments, and whole lines
//! that no seed file has.

use super::Syntax;

/// Numbers a careless or hostile file holds: non-finite, signed zero, the
/// edges of f32, f64 and the integers, the scene format's own limits and
/// just past them, and spellings TOML or Rust may or may not read.
#[rustfmt::skip]
pub const EXTREMES: &[&str] = &[
    "nan", "-nan", "+nan", "NaN", "inf", "-inf", "+inf", "infinity", "-0", "-0.0", "0", "0.0",
    "1e308", "-1e308", "1.8e308", "1e-308", "5e-324", "-1e-300", "1e-45", "3.4028236e38", "1e39",
    "-1e39", "9223372036854775807", "-9223372036854775808", "9223372036854775808",
    "18446744073709551616", "99999999999999999999999", "4294967295", "4294967296", "-1", "-2", "1",
    "2", "3", "179", "179.0", "178.99", "45.01", "360", "360.0000001", "1000", "1001", "1e5",
    "100000.1", "1e6", "1000000.5", "1e-6", "1e-7", "1e8", "0x10", "0o7", "0b1", "1_000", "1__0",
    "1e", ".5", "5.", "+1", "1e+1000", "0.1", "0.5", "10", "-10.5", "1.0e-3",
];

/// Keys a scene or a spec has, table names, and near misses.
#[rustfmt::skip]
pub const TOML_NAMES: &[&str] = &[
    "eye", "target", "up", "fov_y_deg", "near", "far", "shift", "color", "type", "direction",
    "position", "range", "spot_angle_deg", "radius", "angular_radius_deg", "mesh", "translate",
    "rotate_deg", "scale", "casts_shadow", "frames", "pan_deg", "dolly", "camera", "ambient",
    "lights", "objects", "camera_path", "variant", "title", "section", "task", "snapshot_counters",
    "width", "height", "scene", "metric", "at_most", "at_least", "at_most_variant",
    "at_least_variant", "factor", "slack", "hidden", "above", "below", "above_variant",
    "below_variant", "say", "hint", "exercise", "fix", "exercise.check", "exercise.hint", "check",
    "Eye", "colour", "typ", "x", "\"eye\"", "\"a\\nb\"", "a.b", "eye.x", "'type'", "",
    "camera.eye", "lights.type", "objects[0]", "\"\"",
];

/// Values of every TOML type, and words the formats give meaning to.
#[rustfmt::skip]
pub const TOML_VALUES: &[&str] = &[
    "\"str\"", "\"\"", "\"infinite\"", "\"Infinite\"", "true", "false", "[]", "[1]", "[1, 2]",
    "[1, 2, 3]", "[1, 2, 3, 4]", "[\"a\", \"b\", \"c\"]", "[[1, 2, 3]]", "{}", "{ x = 1 }",
    "1979-05-27T07:32:00Z", "07:32:00", "1", "1.5", "-1", "0", "nan", "inf", "-inf", "1e308",
    "'lit'", "\"\"\"multi\nline\"\"\"", "[1, \"a\", true]", "[nan, 0, 0]", "[inf, 1, 1]",
    "[0, 0, 0]", "[1e300, 0, 0]", "[0, -1e-300, 0]", "\"exercise_x\"", "\"default\"", "\"cube\"",
    "\"plane.obj\"", "\"../assets/cube.obj\"", "\"lesson_02_smooth_box.obj\"", "\"a\\nb\"",
    "\"a\\u0000b\"", "\"counters.\"", "\"camera_path.shimmer_pct\"", "\"spot\"", "\"point\"",
    "\"directional\"", "\"sun\"", "\"lesson_02.toml\"", "\"../Cargo.toml\"",
    "\"misclassified_pct\"", "[10, -10]", "[11, 0]",
];

/// OBJ tags, and near misses.
#[rustfmt::skip]
pub const OBJ_NAMES: &[&str] = &[
    "v", "vn", "vt", "vp", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib", "#", "V", "F", "vv",
    "fo", "", "\\",
];

/// Arguments of OBJ lines: counts, index forms, non-numbers.
#[rustfmt::skip]
pub const OBJ_VALUES: &[&str] = &[
    "", "1", "1 2", "1 2 3", "1 2 3 4", "1 2 3 4 5 6 7", "a b c", "1/1 2/2 3/3", "1//1 2//2 3//3",
    "1/1/1 2/2/2 3/3/3", "-1 -2 -3", "0 0 0", "nan nan nan", "inf 0 0", "1e39 0 0", "1 2 3 0",
    "1/2/3/4 5 6", "//", "1/ 2/ 3/", "x.mtl", "4294967295 1 2", "-4294967296 1 2",
    "99999999999999999999 1 2", "1 1 1", "0.5 0.5", "1 2 3 \\",
];

/// Lines no seed has, that each format gives meaning to or must refuse.
#[rustfmt::skip]
pub fn extra_lines(syntax: Syntax) -> &'static [&'static str] {
    match syntax {
        Syntax::Toml => &[
            "[camera]", "[[lights]]", "[[objects]]", "[ambient]", "[camera_path]", "[[exercise]]",
            "[[exercise.check]]", "[[exercise.hint]]", "[[fix]]", "[lights]", "[objects]",
            "[camera.eye]", "[[camera]]", "type = \"spot\"", "type = \"point\"",
            "far = \"infinite\"", "mesh = \"missing.obj\"", "mesh = \"../assets/cube.obj\"",
            "mesh = \"degenerate.obj\"", "mesh = \"torus\"", "mesh = \"knot\"", "radius = 0.5",
            "angular_radius_deg = 0.27", "range = 1e300", "spot_angle_deg = 178.9", "frames = 2",
            "frames = 1001", "pan_deg = 360", "dolly = 99999", "shift = [10, -10]",
            "hidden = true", "at_most = 1.0", "at_most = nan", "at_least = inf",
            "at_least_variant = \"pcf\"", "metric = \"counters.draws\"",
            "metric = \"camera_path.shimmer_pct\"", "hint = 1", "hint = 0",
            "variant = \"exercise_x\"", "say = \"{value}\"", "scene = \"lesson_02.toml\"",
            "scene = \"default\"", "factor = nan", "slack = inf", "width = 0",
            "height = 4294967296", "x = \"\"\"", "\"\"\"", "a = 'unterminated", "[", "]]", "=",
            "key", "# comment", "\\", "x = [", "x = {", "\u{feff}", "\r", "eye = [1, 2, 3] x",
        ],
        Syntax::Obj => &[
            "v 0 0 0", "v 1 0 0", "v 0 1 0", "v 1 2 3 4", "v 1 2 3 0", "v 1 2 3 0.5 0.5 0.5",
            "v 1 2", "v nan 0 0", "v 1e39 0 0", "v 1e6 0 0", "v 1000001 0 0", "vn 0 0 0",
            "vn nan 0 1", "vn 0 1 0", "vn 1e30 1e30 1e30", "vt 0.5", "vt 0 0", "vt 1 2 3",
            "f 1 2 3", "f 3 2 1", "f 1/1/1 2/2/2 3/3/3", "f 1//1 2//2 3//3", "f 1/1 2/2 3/3",
            "f -1 -2 -3", "f 1 2", "f 1 2 3 4 5 6", "f 0 1 2", "f 4294967296 1 2",
            "f 4294967295 1 2", "f -4294967296 1 2", "f 1/ 2/ 3/", "f 1/2/3/4 2 3", "f a b c", "f",
            "o obj", "o", "g group", "g", "s off", "s 1", "usemtl mat", "mtllib a.mtl", "mtllib",
            "l 1 2", "p 1", "# comment", "\\", "v 1 2 \\", "f 1 2 \\", "\r",
        ],
    }
}
