//! Unit tests of `common::scene` (kept apart so the module stays short).

use super::*;

const HEAD: &str = "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n[[lights]]\ntype = \"directional\"\ndirection = [-0.4, -1.0, -0.3]\n";

fn parse(text: &str) -> Result<Scene> {
    Scene::parse(text, "s.toml", Path::new("."))
}

#[test]
fn parses_the_documented_example() {
    let s = parse(&format!(
        "{HEAD}[[lights]]\ntype = \"spot\"\nposition = [0.0, 3.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\nrange = 20.0\nspot_angle_deg = 40.0\n[[objects]]\nmesh = \"plane\"\nscale = 10.0\n[[objects]]\nmesh = \"cube\"\ntranslate = [1.0, 0.5, 0.0]\nrotate_deg = [0.0, 90.0, 0.0]\nscale = [1.0, 2.0, 1.0]\ncasts_shadow = false\n"
    ))
    .unwrap();
    assert_eq!(s.lights.len(), 2);
    assert_eq!(s.objects.len(), 2);
    assert!(!s.objects[1].casts_shadow);
    assert_eq!(s.camera.far, Far::Finite(100.0));
    // T * Rz * Ry * Rx * S: +X of the scaled cube turns to -Z under a 90° yaw.
    let p = s.objects[1]
        .model
        .transform_point3(DVec3::new(0.5, 0.0, 0.0));
    assert!((p - DVec3::new(1.0, 0.5, -0.5)).length() < 1e-9, "{p}");
}

#[test]
fn rotation_order_is_x_then_y_then_z() {
    let s = parse(&format!(
        "{HEAD}[[objects]]\nmesh = \"cube\"\nrotate_deg = [90.0, 90.0, 0.0]\n"
    ))
    .unwrap();
    // Rx(90) takes +Y to +Z; then Ry(90) takes +Z to +X.
    let p = s.objects[0].model.transform_vector3(DVec3::Y);
    assert!((p - DVec3::X).length() < 1e-9, "{p}");
}

#[test]
fn infinite_far_plane() {
    let text = HEAD.replace(
        "target = [0.0, 0.5, 0.0]",
        "target = [0.0, 0.5, 0.0]\nfar = \"infinite\"",
    );
    let s = parse(&format!("{text}[[objects]]\nmesh = \"cube\"\n")).unwrap();
    assert_eq!(s.camera.far, Far::Infinite);
}

#[test]
fn camera_shift_defaults_to_zero_and_is_checked() {
    let obj = "[[objects]]\nmesh = \"cube\"\n";
    let s = parse(&format!("{HEAD}{obj}")).unwrap();
    assert_eq!(s.camera.shift, glam::DVec2::ZERO);
    let with = |shift: &str| {
        let text = HEAD.replace("[camera]", &format!("[camera]\nshift = {shift}"));
        parse(&format!("{text}{obj}"))
    };
    assert_eq!(
        with("[0.4, -0.2]").unwrap().camera.shift,
        glam::DVec2::new(0.4, -0.2)
    );
    for bad in ["[11.0, 0.0]", "[0.0, nan]", "[1.0]", "\"left\""] {
        let e = format!("{:#}", with(bad).expect_err(bad));
        assert!(e.contains("shift"), "{bad}: names the field: {e:?}");
        assert!(!e.contains('\n'), "one line: {e:?}");
    }
}

#[test]
fn bad_input_names_field_and_line() {
    let cases: &[(&str, &str)] = &[
        ("[camera]\neye = [1.0, 2.0\n", "s.toml:"),
        (
            &format!("{HEAD}[[objects]]\nmesh = \"nope\"\n"),
            "objects[0].mesh",
        ),
        (
            &format!("{HEAD}[[objects]]\nmesh = \"cube\"\nscale = 0.0\n"),
            "objects[0].scale",
        ),
        (
            &format!("{HEAD}[[objects]]\nmesh = \"cube\"\ncolor = [1.0, nan, 0.0]\n"),
            "objects[0].color",
        ),
        (
            &HEAD.replace("[-0.4, -1.0, -0.3]", "[0.0, 0.0, 0.0]"),
            "lights[0].direction: zero-length",
        ),
        (
            &format!(
                "{}[[objects]]\nmesh = \"cube\"\n",
                HEAD.replace("directional", "laser")
            ),
            "lights[0].type",
        ),
        (
            &format!(
                "{}[[objects]]\nmesh = \"cube\"\n",
                HEAD.replace("target = [0.0, 0.5, 0.0]", "target = [4.0, 3.0, 6.0]")
            ),
            "camera.target",
        ),
        (
            &format!(
                "{}[[objects]]\nmesh = \"cube\"\n",
                HEAD.replace("[camera]", "[camera]\nnear = 5.0\nfar = 1.0")
            ),
            "camera.far",
        ),
        (HEAD, "objects: the scene needs at least one"),
    ];
    for (text, want) in cases {
        let e = format!("{:#}", parse(text).expect_err(want));
        assert!(e.contains(want), "expected {want:?} in {e:?}");
        assert!(!e.contains('\n'), "one line: {e:?}");
    }
}

#[test]
fn errors_carry_the_line_of_the_table() {
    let text = format!(
        "{HEAD}\n[[objects]]\nmesh = \"cube\"\n\n[[objects]]\nmesh = \"cube\"\nscale = -0.0\n"
    );
    let e = format!("{:#}", parse(&text).unwrap_err());
    let line = text
        .lines()
        .position(|l| l.starts_with("scale = -0.0"))
        .unwrap()
        + 1;
    assert!(
        e.contains(&format!("s.toml:{}", line - 2))
            || e.contains(&format!("s.toml:{}", line - 1))
            || e.contains(&format!("s.toml:{line}")),
        "{e}"
    );
}
