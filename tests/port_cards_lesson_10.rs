//! Lesson 10's ports against their cards (`lessons/lesson_10/port_cards.rs`):
//! every port has a card, every card is whole, and every constant and
//! formula a card records is the one the port runs: in `peers.rs` (taps,
//! map sizes, light sizes, the variance maps' numbers) and in
//! `shaders/lesson_10/peers.wgsl` (tap positions, texel sizes, the depth
//! conventions and penumbra formulas). Changing a port's constant, or its
//! card's, fails here.

use common::ports::{PortCard, Role};
use workbook::lesson_02::bias::ShadowBias;
use workbook::lesson_10::map_sets::MapPass;
use workbook::lesson_10::peers::{self, Peer};
use workbook::lesson_10::port_cards::{self, CARDS};
use workbook::lesson_10::soft::LightGeometry;

const PEERS_WGSL: &str = include_str!("../shaders/lesson_10/peers.wgsl");

fn card(variant: &str) -> &'static PortCard {
    CARDS
        .iter()
        .find(|c| c.variant == variant)
        .unwrap_or_else(|| panic!("no card for {variant}"))
}

/// A spot of radius 0.25 with a 60° cone and a sun of 1° angular radius.
fn spot() -> LightGeometry {
    let tan_half = 30f32.to_radians().tan();
    LightGeometry {
        perspective: true,
        near: 0.05,
        far: 20.0,
        size: 0.25,
        nearest_caster: 2.0,
        uv_per: [0.5 / tan_half; 2],
    }
}

fn sun() -> LightGeometry {
    LightGeometry {
        perspective: false,
        near: 0.0,
        far: 30.0,
        size: 1f32.to_radians().tan(),
        nearest_caster: 5.0,
        uv_per: [0.05, 0.05],
    }
}

/// The numbers of WGSL constant `name` (`const NAME = array<…>(…);` or
/// `const NAME: f32 = …;`), in order.
fn wgsl_numbers(name: &str) -> Vec<f64> {
    let start = PEERS_WGSL
        .find(&format!("const {name}"))
        .unwrap_or_else(|| panic!("peers.wgsl has no const {name}"));
    let rest = &PEERS_WGSL[start..];
    let end = rest.find(';').expect("a const ends with ;");
    let body = &rest[..end];
    // Past the type: the array's opening parenthesis, or the `=`.
    let body = match body.find(">(") {
        Some(i) => &body[i + 2..],
        None => &body[body.find('=').expect("=") + 1..],
    };
    let body = body.replace("vec2<f32>", " ");
    body.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .filter(|t| !t.is_empty() && *t != "-")
        .map(|t| {
            t.parse()
                .unwrap_or_else(|_| panic!("{name}: {t:?} is not a number"))
        })
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * a.abs().max(1.0)
}

fn assert_list(name: &str, card: &[f64], port: &[f64]) {
    assert_eq!(
        card.len(),
        port.len(),
        "{name}: card and port differ in count"
    );
    for (i, (a, b)) in card.iter().zip(port).enumerate() {
        assert!(close(*a, *b), "{name}[{i}]: card {a}, port {b}");
    }
}

/// The port's WGSL holds `line` (its translation of the card's formula).
fn assert_wgsl(variant: &str, constant: &str, line: &str) {
    let c = card(variant).constant(constant);
    assert!(
        PEERS_WGSL.contains(line),
        "{variant}: its card's {constant} ({:?}) is run as `{line}`, which peers.wgsl no longer holds",
        c.value
    );
}

#[test]
fn every_port_has_a_whole_card_and_every_card_a_port() {
    for c in CARDS {
        assert!(c.problems().is_empty(), "{:?}", c.problems());
        for g in [spot(), sun()] {
            assert!(
                peers::port(c.variant, &g).is_some(),
                "card {} names no port",
                c.variant
            );
        }
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lesson_10"))
        .arg("--list-variants")
        .output()
        .expect("lesson_10 --list-variants");
    let listed = String::from_utf8_lossy(&out.stdout);
    let ports: Vec<&str> = listed
        .split_whitespace()
        .filter(|v| peers::port(v, &spot()).is_some())
        .collect();
    assert_eq!(ports.len(), CARDS.len(), "ports {ports:?}");
    for p in ports {
        card(p);
    }
}

#[test]
fn filament_pcss_runs_its_card() {
    let c = card("filament_pcss");
    assert_list(
        "poissonDisk[0..16]",
        c.list("poissonDisk[0..16]"),
        &wgsl_numbers("FILAMENT_POISSON_16"),
    );
    assert_eq!(
        c.list("poissonDisk[0..16]"),
        port_cards::FILAMENT_POISSON_16
    );
    let taps = wgsl_numbers("FILAMENT_PCSS_TAPS")[0];
    assert_eq!(c.num("PCSS_SHADOW_BLOCKER_SEARCH_TAP_COUNT"), taps);
    assert_eq!(c.num("PCSS_SHADOW_FILTER_TAP_COUNT"), taps);
    let Some(Peer::FilamentPcss { bulb_radius, .. }) = peers::port(c.variant, &sun()) else {
        panic!("filament_pcss is Filament's PCSS");
    };
    assert!(close(c.num("shadowBulbRadius"), bulb_radius as f64));
    for g in [spot(), sun()] {
        let p = peers::port(c.variant, &g).unwrap();
        let (search, filter, _) = p.taps();
        assert_eq!((search as f64, filter as f64), (taps, taps));
        assert_eq!(c.num("mapSize"), p.map_size() as f64);
    }
    assert!(c
        .text("penumbraRatio (directional)")
        .contains("(1.0 - z_blocker)"));
    assert_wgsl(
        c.variant,
        "penumbraRatio (directional)",
        "return (z_b - z_r) / (1.0 - z_b);",
    );
    assert_wgsl(
        c.variant,
        "penumbraRatio (spot)",
        "return (k + z_b) / (k + z_r) - 1.0;",
    );
    assert_wgsl(
        c.variant,
        "nearOverFarMinusNear",
        "let k = soft.near / (soft.far - soft.near);",
    );
    assert_wgsl(c.variant, "z_occSum", "z_occ_sum += z_occ * o;");
    assert_wgsl(c.variant, "early exit", "if z_occ_sum == 0.0 {");
    assert_wgsl(
        c.variant,
        "getPenumbraLs",
        "penumbra = penumbra / light_distance(s.z);",
    );
}

#[test]
fn filament_evsm_runs_its_card() {
    let c = card("filament_evsm");
    let Some(Peer::FilamentEvsm(v)) = peers::port(c.variant, &spot()) else {
        panic!("filament_evsm is Filament's VSM");
    };
    let exponent = c.num("vsmExponent (16-bit moments)");
    assert!(close(v.exponent.expect("an EVSM") as f64, exponent));
    assert!(c
        .text("vsmDepthScale")
        .contains("minVarianceScale * 0.01f * vsmExponent"));
    let depth_scale = c.num("minVarianceScale") * 0.01 * exponent;
    assert!(
        close(v.min_variance as f64, depth_scale * depth_scale),
        "least variance {} against (minVarianceScale · 0.01 · vsmExponent)² = {}",
        v.min_variance,
        depth_scale * depth_scale
    );
    assert!(close(v.bleed.0 as f64, c.num("lightBleedReduction")));
    assert_eq!(v.bleed.1, 1.0);
    assert_eq!(v.blur as f64, c.num("blurWidth"));
    assert_eq!(v.negative, None, "ELVSM is off by default");
    let p = peers::port(c.variant, &spot()).unwrap();
    assert_eq!(c.num("mapSize"), p.map_size() as f64);
}

#[test]
fn bevy_pcss_or_pcf_runs_its_card() {
    let c = card("bevy_pcss_or_pcf");
    assert!(close(
        c.num("SPOT_SHADOW_TEXEL_SIZE"),
        wgsl_numbers("BEVY_SPOT_SHADOW_TEXEL_SIZE")[0]
    ));
    assert_list(
        "D3D_SAMPLE_POINT_POSITIONS",
        c.list("D3D_SAMPLE_POINT_POSITIONS"),
        &wgsl_numbers("BEVY_D3D_SAMPLE_POINT_POSITIONS"),
    );
    assert_list(
        "SPIRAL_OFFSET_0_..7_",
        c.list("SPIRAL_OFFSET_0_..7_"),
        &wgsl_numbers("BEVY_SPIRAL_OFFSETS"),
    );
    assert!(close(
        c.num("DEFAULT_SHADOW_MAP_NEAR_Z (spot)"),
        wgsl_numbers("BEVY_NEAR_Z")[0]
    ));
    // The spot: PCSS, sized by the light's radius.
    let g = spot();
    let p = peers::port(c.variant, &g).unwrap();
    assert_eq!(p, Peer::BevyPcss { light_size: g.size });
    let (search, filter, _) = p.taps();
    assert_eq!(
        (search as f64, filter as f64),
        (c.num("PCSS taps"), c.num("PCSS taps"))
    );
    // The sun: no PCSS (soft_shadow_size None), Bevy's default filter.
    let p = peers::port(c.variant, &sun()).unwrap();
    assert_eq!(p, Peer::BevyCastano);
    assert_eq!(peers::port("bevy_gaussian", &sun()), Some(p));
    assert!(c
        .text("depth (spot)")
        .contains("near_z / -projected_position.z"));
    assert_wgsl(
        c.variant,
        "depth (spot)",
        "return BEVY_NEAR_Z / light_distance(z);",
    );
    assert_wgsl(
        c.variant,
        "blur_size",
        "let blur_size = max((z_blocker - depth) * light_size / depth, 0.5);",
    );
    assert_wgsl(
        c.variant,
        "Jimenez spacing",
        "let f = bevy_map(0.00390625, 0.022949219, 0.015, 0.035, texel_size);",
    );
    assert_wgsl(
        c.variant,
        "search uv_offset_scale",
        "let search_scale = light_size / (texel_size * shadow_map_size);",
    );
    assert_wgsl(
        c.variant,
        "shadow_map_size", // not a counter: Bevy's shader variable
        "let shadow_map_size = f32(textureDimensions(shadow_map).x);",
    );
    assert_wgsl(
        c.variant,
        "blocker test",
        "sum += select(vec2<f32>(0.0), vec2<f32>(sampled, 1.0), sampled >= depth);",
    );
    assert_wgsl(
        c.variant,
        "interleaved_gradient_noise",
        "let xy = pixel + 5.588238 * f32(1u % 64u);",
    );
}

/// The pass a card's shadow pass describes: the faces it culls (the
/// opposite of those it draws) and its hardware offset.
fn pass(cull: Option<wgpu::Face>, constant: i32, slope_scale: f32) -> MapPass {
    MapPass::Renderer {
        cull,
        bias: wgpu::DepthBiasState {
            constant,
            slope_scale,
            clamp: 0.0,
        },
    }
}

#[test]
fn bevys_ports_draw_its_map_and_move_its_receiver() {
    for variant in ["bevy_gaussian", "bevy_pcss_or_pcf"] {
        let c = card(variant);
        // Spot maps are layers of the directional texture: its size.
        assert!(c.text("spot maps").contains("DirectionalLightShadowMap"));
        let size = c.num("DirectionalLightShadowMap size (spots too)");
        // Front faces drawn (back culled), no hardware offset.
        assert!(c
            .text("StandardMaterial cull_mode")
            .contains("Some(Face::Back)"));
        assert!(c
            .text("shadow pass DepthBiasState")
            .contains("(0), slope_scale 0.0"));
        let depth_bias = c.num("shadow_depth_bias (spot and directional)");
        let normal_bias = c.num("shadow_normal_bias (spot and directional)");
        assert!(c.text("spot normal bias").contains("SQRT_2"));
        for g in [spot(), sun()] {
            let p = peers::port(variant, &g).unwrap();
            assert_eq!(p.map_size() as f64, size, "{variant}");
            assert_eq!(p.map_pass(), pass(Some(wgpu::Face::Back), 0, 0.0));
            let r = p.receiver_bias();
            assert!(close(r.toward_light_world as f64, depth_bias));
            assert!(close(
                r.normal_flat as f64,
                normal_bias * std::f64::consts::SQRT_2
            ));
            assert_eq!(p.receiver_normal_sin(), 0.0);
        }
    }
    assert_eq!(card("bevy_gaussian").role, Role::Default);
}

#[test]
fn filaments_ports_draw_its_map_and_move_its_receiver() {
    for variant in ["filament_pcf", "filament_pcss"] {
        let c = card(variant);
        let offset = c.list("polygonOffsetSlope, polygonOffsetConstant");
        assert!(c.text("mCullingMode").contains("CullingMode::BACK"));
        assert!(c.text("computeLightSpacePosition").contains("sinTheta"));
        let scaled = c.text("normalBias scaled");
        assert!(
            scaled.contains("a cascade 0.5 * normalBias") && scaled.contains("a spot normalBias")
        );
        for g in [spot(), sun()] {
            let p = peers::port(variant, &g).unwrap();
            // Filament's constant is in 16-bit units (2^-16), wgpu's in
            // Depth32Float's (2^-24 for depths in [0.5, 1)).
            let want = pass(
                Some(wgpu::Face::Back),
                (offset[1] * 256.0) as i32,
                offset[0] as f32,
            );
            assert!(c.departures.iter().any(|d| d.what == "its 16-bit map"));
            assert_eq!(p.map_pass(), want, "{variant}");
            let r = p.receiver_bias();
            assert!(close(r.toward_light_world as f64, c.num("constantBias")));
            let half = if g.perspective { 1.0 } else { 0.5 };
            assert!(close(
                p.receiver_normal_sin() as f64,
                half * c.num("normalBias")
            ));
            assert_eq!(p.map_size() as f64, c.num("mapSize"));
        }
    }
    // Filament's VSM: no offsets anywhere, the material's culling.
    let c = card("filament_evsm");
    assert!(c.text("polygonOffset").contains("0 when the view has VSM"));
    assert!(c.text("offsets under VSM").contains("ignored"));
    for g in [spot(), sun()] {
        let p = peers::port(c.variant, &g).unwrap();
        assert_eq!(p.map_pass(), pass(Some(wgpu::Face::Back), 0, 0.0));
        assert_eq!(p.receiver_bias(), ShadowBias::NONE);
        assert_eq!(p.receiver_normal_sin(), 0.0);
    }
}

#[test]
fn filament_pcf_runs_its_card() {
    let c = card("filament_pcf");
    let p = peers::port(c.variant, &spot()).unwrap();
    assert_eq!(p.taps().1, 4);
    assert!(c
        .text("ShadowSample_PCF_Low")
        .contains("sum * (1.0 / 16.0)"));
    assert_wgsl(
        c.variant,
        "ShadowSample_PCF_Low",
        "return sum * (1.0 / 16.0);",
    );
    assert_wgsl(
        c.variant,
        "uw, vw",
        "let uw = vec2<f32>(3.0 - 2.0 * st.x, 1.0 + 2.0 * st.x);",
    );
    assert_wgsl(
        c.variant,
        "u, v",
        "var u = vec2<f32>((2.0 - st.x) / uw.x - 1.0, st.x / uw.y + 1.0);",
    );
}

#[test]
fn godot_soft_low_runs_its_card() {
    let c = card("godot_soft_low");
    let g = spot();
    let Some(Peer::GodotSoft {
        taps, size, scale, ..
    }) = peers::port(c.variant, &g)
    else {
        panic!("godot_soft_low is Godot's soft shadow");
    };
    assert_eq!(taps as f64, c.num("SOFT_LOW penumbra samples"));
    assert_eq!(scale, 1.0, "{}", c.text("soft_shadow_scale"));
    // (size · 0.5 / radius) / (half_np / z_near) · width, size the diameter.
    let tan_half = 0.5 / g.uv_per[0];
    let godot = (2.0 * g.size * 0.5 / g.far) / tan_half;
    assert!(
        close(size as f64, godot as f64),
        "spot size {size} against {godot}"
    );
    let s = sun();
    let Some(Peer::GodotSoft { size, .. }) = peers::port(c.variant, &s) else {
        panic!("godot_soft_low is Godot's soft shadow");
    };
    let diameter = 2.0 * s.size.atan();
    assert!(
        close(size as f64, diameter.tan() as f64),
        "softshadow_angle = tan(angular diameter)"
    );
    assert!(close(c.num("get_vogel_disk golden_angle"), 2.4));
    assert_wgsl(
        c.variant,
        "get_vogel_disk golden_angle",
        "let theta = f32(i) * 2.4;",
    );
    assert_wgsl(
        c.variant,
        "penumbra (spot)",
        "let penumbra = (-z_norm + blocker_average) / (1.0 - blocker_average);",
    );
    assert_wgsl(
        c.variant,
        "z_norm (spot)",
        "z_norm = light_distance(s.z) / soft.far;",
    );
    assert_wgsl(
        c.variant,
        "uv_size (spot)",
        "uv_size = vec2<f32>(soft.size * z_norm * soft.scale);",
    );
    assert_wgsl(c.variant, "blocker test", "if d > z {");
}

#[test]
fn godot_pcf_runs_its_card() {
    let c = card("godot_pcf");
    assert_eq!(c.num("PARAM_SIZE (light_size)"), 0.0);
    for g in [spot(), sun()] {
        let Some(Peer::GodotPcf { taps, radius, .. }) = peers::port(c.variant, &g) else {
            panic!("godot_pcf is Godot's PCF");
        };
        assert_eq!(taps as f64, c.num("SOFT_LOW soft_shadow_samples"));
        assert!(c
            .text("soft_shadow_scale (size 0)")
            .contains("shadow_blur (1.0) * shadows_quality_radius"));
        assert!(close(
            radius as f64,
            c.num("SOFT_LOW shadows_quality_radius")
        ));
    }
    assert_wgsl(
        c.variant,
        "sample_pcf_shadow",
        "avg += textureSampleCompareLevel(shadow_map, shadow_compare, s.xy + shadow_pixel_size * (disk_rotation * godot_vogel(i, n)), s.z);",
    );
}

#[test]
fn godots_ports_move_the_receiver_along_its_normal() {
    for variant in ["godot_pcf", "godot_soft_low"] {
        let c = card(variant);
        assert!(c
            .text("shadow_normal_bias")
            .contains("SHADOW_NORMAL_BIAS (1.0) * shadow_texel_size * 10.0"));
        assert!(c.text("normal_bias (spot)").contains("(1.0 - abs(dot("));
        // normal × light_length × normal_bias × 10 / shadow_size: per
        // texel of the spot at that distance, 10 / (2 tan(cone / 2)).
        assert!(c.text("shadow_texel_size").contains("1.0 / shadow_size"));
        let g = spot();
        let p = peers::port(variant, &g).unwrap();
        let tan_half = 0.5 / g.uv_per[0];
        assert!(close(
            p.receiver_bias().normal as f64,
            10.0 / (2.0 * tan_half as f64)
        ));
        // A sun: its DirectionalLight3D's 2.0 × sin θ, on its first split.
        assert!(c
            .text("shadow_normal_bias (directional)")
            .contains("(2.0 for DirectionalLight3D)"));
        let s = peers::port(variant, &sun()).unwrap();
        assert_eq!(s.receiver_normal_sin(), 2.0);
        assert_eq!(s.receiver_bias().normal, 0.0);
        assert_eq!(s.map_size(), 2048);
        assert_eq!(p.receiver_normal_sin(), 0.0);
        assert_eq!(p.map_size(), 1024);
        // shadow_bias: a spot's 0.03 / 100 × the filter's scale in clip depth
        // over distance / range, 199 × that in metres for its near plane.
        assert!(c
            .text("shadow_bias (spot)")
            .contains("/ (light_length * inv_radius)"));
        let scale = if variant == "godot_pcf" { 2.0 } else { 1.0 };
        let near = c.num("spot near / range");
        let want = c.num("SpotLight3D shadow_bias") / 100.0 * scale * (1.0 / near - 1.0);
        assert!(
            close(p.receiver_bias().toward_light_world as f64, want),
            "{variant}"
        );
        // Its shadow pass was not read to its lines: the lesson's map, said so.
        assert_eq!(p.map_pass(), MapPass::Lesson);
        assert!(c
            .departures
            .iter()
            .any(|d| d.what.contains("its shadow pass")));
    }
}

#[test]
fn threejs_ports_run_their_cards() {
    // PCFShadowMap (the default) and PCFSoftShadowMap draw the back faces
    // of a front-sided material; VSM draws its front faces.
    for variant in ["threejs_pcf", "threejs_pcf_soft"] {
        let c = card(variant);
        assert!(c.text("shadowSide").contains("FrontSide: BackSide"));
        assert!(c
            .text("Material.side, shadowSide")
            .starts_with("FrontSide, null"));
        for g in [spot(), sun()] {
            let p = peers::port(variant, &g).unwrap();
            assert_eq!(
                p.map_pass(),
                pass(Some(wgpu::Face::Front), 0, 0.0),
                "{variant}"
            );
            assert_eq!(c.list("bias, normalBias"), &[0.0, 0.0]);
            assert_eq!(p.receiver_bias(), ShadowBias::NONE);
            assert!(!p.params().receiver_plane, "three.js has no receiver plane");
            assert_eq!(p.map_size() as f64, c.num("mapSize"));
        }
    }
    let vsm = card("threejs_vsm");
    assert!(vsm.text("VSM side").contains("material.side"));
    let p = peers::port(vsm.variant, &spot()).unwrap();
    assert_eq!(p.map_pass(), pass(Some(wgpu::Face::Back), 0, 0.0));
    assert_eq!(p.receiver_bias(), ShadowBias::NONE);

    let pcf = card("threejs_pcf");
    let p = peers::port(pcf.variant, &spot()).unwrap();
    assert_eq!(p, Peer::ThreePcf);
    assert_eq!(p.taps().1 as f64, pcf.num("PCF taps"));
    assert_wgsl(
        pcf.variant,
        "vogelDiskSample",
        "let golden_angle = 2.399963229728653;",
    );
    assert_wgsl(pcf.variant, "PCF taps", "return shadow * 0.2;");

    let soft = card("threejs_pcf_soft");
    let p = peers::port(soft.variant, &spot()).unwrap();
    assert_eq!(p, Peer::ThreePcfSoft);
    assert_eq!(p.taps().1 as f64, soft.num("PCF_SOFT taps"));
    assert_wgsl(soft.variant, "PCF_SOFT weights", "return sum / 9.0;");

    let Some(Peer::ThreeVsm(v, blur)) = peers::port(vsm.variant, &spot()) else {
        panic!("threejs_vsm is three.js's VSM");
    };
    assert_eq!(blur.samples as f64, vsm.num("blurSamples"));
    assert_eq!(blur.radius as f64, vsm.num("radius"));
    assert_list(
        "bleed cut",
        vsm.list("bleed cut"),
        &[v.bleed.0 as f64, v.bleed.1 as f64],
    );
    let p = peers::port(vsm.variant, &sun()).unwrap();
    assert_eq!(p.map_size() as f64, vsm.num("mapSize"));
    assert_wgsl(
        vsm.variant,
        "VSM getShadow",
        "let hard_shadow = step(s.z, mean);",
    );
    assert_wgsl(
        vsm.variant,
        "VSM getShadow",
        "variance = max(variance, 0.0000001);",
    );
    assert_wgsl(vsm.variant, "moments", "var variance = m.y * m.y;");
}

#[test]
fn every_card_says_default_or_option_as_its_port_is() {
    let mut defaults = std::collections::BTreeSet::new();
    for c in CARDS {
        for g in [spot(), sun()] {
            let p = peers::port(c.variant, &g).unwrap();
            let default = c.role == Role::Default;
            // bevy_pcss_or_pcf runs Bevy's default on a sun: its card is
            // the option's, which it is where it differs.
            if c.variant != "bevy_pcss_or_pcf" || g.perspective {
                assert_eq!(p.is_default(), default, "{}", c.variant);
            }
        }
        if c.role == Role::Default {
            assert!(
                defaults.insert(c.renderer),
                "two defaults for {}",
                c.renderer
            );
        }
    }
    // Every renderer's default is ported beside its options.
    let renderers: std::collections::BTreeSet<_> = CARDS.iter().map(|c| c.renderer).collect();
    assert_eq!(defaults, renderers);
}
