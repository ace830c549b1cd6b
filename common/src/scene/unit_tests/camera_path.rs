//! Unit tests of `common::scene::camera_path` (kept apart so the module stays short).

use glam::DVec3;

use super::*;
use crate::scene::{Far, Scene};

fn camera() -> Camera {
    Camera {
        eye: DVec3::new(4.0, 3.0, 6.0),
        target: DVec3::new(0.0, 0.5, 0.0),
        up: DVec3::Y,
        fov_y_deg: 50.0,
        near: 0.1,
        far: Far::Finite(100.0),
        shift: glam::DVec2::ZERO,
    }
}

fn path(frames: u32, pan_deg: f64, dolly: f64) -> CameraPath {
    CameraPath {
        frames,
        pan_deg,
        dolly,
    }
}

/// The yaw (degrees, about +Y) of a camera's view direction.
fn yaw_deg(c: &Camera) -> f64 {
    let d = c.target - c.eye;
    d.x.atan2(d.z).to_degrees()
}

#[test]
fn frame_0_is_the_scene_camera_and_the_last_has_the_whole_path() {
    let base = camera();
    for n in [2, 3, 16, 17] {
        let cams = path_cameras(&base, &path(n, 3.0, 2.0));
        assert_eq!(cams.len(), n as usize);
        assert_eq!(cams[0], base, "{n} frames");
        let last = cams.last().unwrap();
        let turned = yaw_deg(last) - yaw_deg(&base);
        assert!((turned - 3.0).abs() < 1e-9, "{n} frames: yaw {turned}");
        // The eye moved 2 along the view direction at the pan's end.
        let forward = (last.target - last.eye).normalize();
        let moved = last.eye - base.eye;
        assert!(
            (moved - forward * 2.0).length() < 1e-9,
            "{n} frames: {moved}"
        );
        // Pan about up keeps the view's elevation; up, fov, near, far kept.
        let elevation = |c: &Camera| (c.target - c.eye).normalize().y;
        assert!((elevation(last) - elevation(&base)).abs() < 1e-12);
        assert_eq!(
            (last.up, last.fov_y_deg, last.far),
            (base.up, 50.0, base.far)
        );
    }
}

#[test]
fn the_path_pans_then_dollies_monotonically() {
    let base = camera();
    let cams = path_cameras(&base, &path(16, 3.0, 2.0));
    let (yaws, moved): (Vec<f64>, Vec<f64>) = cams
        .iter()
        .map(|c| (yaw_deg(c) - yaw_deg(&base), (c.eye - base.eye).length()))
        .unzip();
    // Frames 0..=8 pan with the eye still; frames 8..=15 dolly at a fixed yaw.
    for i in 1..16 {
        assert!(yaws[i] >= yaws[i - 1] - 1e-12, "yaw at {i}: {yaws:?}");
        assert!(moved[i] >= moved[i - 1] - 1e-12, "dolly at {i}: {moved:?}");
        if i <= 8 {
            assert!(yaws[i] > yaws[i - 1] && moved[i] == 0.0, "pan at {i}");
        } else {
            assert!(
                (yaws[i] - 3.0).abs() < 1e-9 && moved[i] > moved[i - 1],
                "dolly at {i}"
            );
        }
    }
    // Equal steps: 3/8 degree, then 2/7.
    assert!((yaws[1] - 3.0 / 8.0).abs() < 1e-9);
    assert!((moved[9] - 2.0 / 7.0).abs() < 1e-9);
}

const SCENE: &str = "[camera]\neye = [4.0, 3.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\n\
    [[lights]]\ntype = \"directional\"\ndirection = [-0.4, -1.0, -0.3]\n\
    [[objects]]\nmesh = \"cube\"\n";

fn parse(table: &str) -> anyhow::Result<Scene> {
    let text = format!("{SCENE}[camera_path]\n{table}");
    Scene::parse(&text, "s.toml", std::path::Path::new("."))
}

#[test]
fn a_scene_reads_its_camera_path() {
    let s = parse("frames = 20\npan_deg = 3\ndolly = 2.5\n").unwrap();
    assert_eq!(s.camera_path, Some(path(20, 3.0, 2.5)));
    // frames defaults to 16, and one of pan_deg and dolly is enough.
    let s = parse("dolly = -1.0\n").unwrap();
    assert_eq!(s.camera_path, Some(path(16, 0.0, -1.0)));
    let s = Scene::parse(SCENE, "s.toml", std::path::Path::new(".")).unwrap();
    assert_eq!(s.camera_path, None);
}

#[test]
fn bad_camera_paths_are_one_line_naming_the_field() {
    for (table, want) in [
        (
            "frames = 1\npan_deg = 3.0\n",
            "camera_path.frames: must be in [2, 1000], got 1",
        ),
        ("frames = 1001\npan_deg = 3.0\n", "camera_path.frames"),
        (
            "frames = 2.5\npan_deg = 3.0\n",
            "camera_path.frames: expected a whole number",
        ),
        (
            "pan_deg = 0.0\ndolly = 0\n",
            "camera_path: pan_deg and dolly are both 0",
        ),
        ("frames = 8\n", "camera_path: pan_deg and dolly are both 0"),
        ("pan_deg = nan\n", "camera_path.pan_deg: must be in"),
        ("pan_deg = 1e300\n", "camera_path.pan_deg: must be in"),
        ("dolly = inf\n", "camera_path.dolly: must be in"),
        ("dolly = -1e9\n", "camera_path.dolly: must be in"),
        ("dolly = \"far\"\n", "camera_path.dolly: expected a number"),
        ("pan = 3.0\n", "unknown field `pan`"),
    ] {
        let e = format!("{:#}", parse(table).unwrap_err());
        assert!(e.starts_with("s.toml:"), "{table:?}: {e}");
        assert!(e.contains(want), "{table:?}: {e}");
        assert!(!e.contains('\n'), "{table:?}: {e}");
    }
}

/// One light's states from (reference lit, technique lit) pairs; `None`
/// where the pixel is no receiver.
fn frame(states: &[PixelState]) -> Vec<Vec<PixelState>> {
    vec![states.to_vec()]
}

#[test]
fn screen_mismatch_counts_technique_flips_the_reference_does_not_make() {
    let (lit, shadow) = (Some((true, true)), Some((false, false)));
    let mut s = Shimmer::new(4, 1);
    // Pixel 0: both flip (a moving shadow edge). Pixel 1: the technique
    // flips alone. Pixel 2: steady but wrong. Pixel 3: a receiver in one
    // frame only: not counted.
    s.add_frame(frame(&[lit, lit, Some((true, false)), None]));
    s.add_frame(frame(&[
        shadow,
        Some((true, false)),
        Some((true, false)),
        lit,
    ]));
    // Pixel 1 flips back: a mismatch again; pixel 0 steady.
    s.add_frame(frame(&[shadow, lit, Some((true, false)), None]));
    let r = s.report();
    assert_eq!(r.frames, 3);
    // 2 pairs x 3 pixels counted; mismatch 2, reference flips 1, technique 3.
    assert!(
        (r.screen_mismatch_pct - 100.0 * 2.0 / 6.0).abs() < 1e-9,
        "{r:?}"
    );
    assert!((r.reference_flip_pct - 100.0 / 6.0).abs() < 1e-9, "{r:?}");
    assert!(
        (r.technique_flip_pct - 100.0 * 3.0 / 6.0).abs() < 1e-9,
        "{r:?}"
    );
    // No probe was added: no world-locked shimmer, and a black picture.
    assert_eq!(r.shimmer_pct, 0.0);
    assert!(s.image(1).pixels().all(|p| p.0[0] == 0));
    let per_frame = [100.0 / 3.0, 50.0, 100.0 / 3.0];
    for (got, want) in r.misclassified_pct_per_frame.iter().zip(per_frame) {
        assert!((got - want).abs() < 1e-9, "{r:?}");
    }
}

#[test]
fn shimmer_counts_flips_of_a_probe_where_both_frames_see_the_surface() {
    let (lit, shadow) = (Some((true, true)), Some((true, false)));
    let mut s = Shimmer::new(4, 1);
    let seen = [true, true, true, false];
    // Pair 1: pixel 1 flips under the next fit (shimmer); pixel 3 flips
    // too, but the next view does not see its surface: not counted.
    let fitted = frame(&[lit, lit, shadow, lit]);
    s.add_probe(&fitted, &frame(&[lit, shadow, shadow, shadow]), &seen);
    s.add_frame(fitted);
    // Pair 2: pixel 1 flips again; pixel 2 is no receiver in the probe.
    let fitted = frame(&[lit, lit, shadow, lit]);
    s.add_probe(&fitted, &frame(&[lit, shadow, None, lit]), &seen);
    s.add_frame(fitted);
    s.add_frame(frame(&[lit, lit, shadow, lit]));
    let r = s.report();
    // Counted: 3 + 2 receivers seen in both; flips: 2.
    assert!((r.shimmer_pct - 100.0 * 2.0 / 5.0).abs() < 1e-9, "{r:?}");
    // Pixel 1 shimmered in both pairs (the most, 255); the rest never.
    let img: Vec<u8> = s.image(1).pixels().map(|p| p.0[0]).collect();
    assert_eq!(img, vec![0, 255, 0, 0]);
}

#[test]
fn a_steady_technique_on_a_moving_shadow_does_not_shimmer() {
    // The technique follows the reference exactly: flips, but no mismatch,
    // and its probes (the same fit) never flip.
    let mut s = Shimmer::new(2, 1);
    for i in 0..4 {
        let on = i % 2 == 0;
        let f = frame(&[Some((on, on)), Some((true, true))]);
        if i < 3 {
            s.add_probe(&f, &f, &[true, true]);
        }
        s.add_frame(f);
    }
    let r = s.report();
    assert_eq!((r.shimmer_pct, r.screen_mismatch_pct), (0.0, 0.0));
    assert_eq!((r.reference_flip_pct, r.technique_flip_pct), (50.0, 50.0));
    assert!(s.image(1).pixels().all(|p| p.0[0] == 0));
}

#[test]
fn a_dolly_out_of_the_world_is_refused_by_name() {
    let text = "[camera]\neye = [999980.0, 1.0, 0.0]\ntarget = [999990.0, 1.0, 0.0]\n\
        [[lights]]\ntype = \"directional\"\ndirection = [0.0, -1.0, 0.0]\n\
        [[objects]]\nmesh = \"cube\"\ntranslate = [999985.0, 0.0, 0.0]\n";
    let parse = |path: &str| {
        let text = format!("{text}[camera_path]\n{path}\n");
        Scene::parse(&text, "s.toml", std::path::Path::new(".")).unwrap()
    };
    check_path(&parse("dolly = 5.0")).unwrap();
    let e = check_path(&parse("dolly = 100000.0"))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("camera_path.dolly: the last eye"), "{e}");
}
