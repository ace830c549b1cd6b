//! Each port against its card. A card (`lessons/lesson_NN/port_cards.rs`)
//! is a transcription of a renderer's source: its constants with the file,
//! commit and lines they were read at. The port keeps its own constants,
//! in Rust or in WGSL. These tests read both and compare them: a port whose
//! constant drifts from its card fails, and so does a card that drifts
//! from its port. Constants that live only in WGSL (LearnOpenGL's disk
//! directions, Bevy's sample positions and weights, Castaño's formulas) are
//! read from the shader's text.
//!
//! The book's "where each port departs" tables are generated from the cards
//! (`common::ports::departures_table`) into `book/src/generated/ports/`;
//! `the_books_departure_tables_are_the_cards` checks them, and with
//! `WORKBOOK_WRITE_PORT_TABLES=1` writes them.

use std::f64::consts::SQRT_2;

use common::measure::counters::{
    FILTER_TAPS_PER_PIXEL, NEAR_PLANE_MM, SHADOW_MAP_SIZE, TAPS, UNCLIPPED_DEPTH,
};
use common::ports::{departures_table, PortCard};
use workbook::lesson_01::shadow_map::SHADOW_FORMAT;
use workbook::lesson_02::bias::{
    ShadowBias, SlopeScaledBias, BEVY_MAP_SIZE, WGPU_EXAMPLE_CULL, WGPU_EXAMPLE_MAP_SIZE,
};
use workbook::lesson_03::pcf::{self, Filter};
use workbook::lesson_04::cube_map::{Storage, CUBE_FORMAT};
use workbook::lesson_04::peers::{self, Peer, BEVY_POINT_NORMAL_BIAS};
use workbook::{lesson_02, lesson_03, lesson_04};

const PCF_WGSL: &str = include_str!("../shaders/lesson_03/pcf.wgsl");
const PEERS_WGSL: &str = include_str!("../shaders/lesson_04/peers.wgsl");

/// Every card of the three lessons, with its lesson's name.
fn all_cards() -> Vec<(&'static str, PortCard)> {
    let lessons: [(&'static str, &'static [PortCard]); 3] = [
        ("lesson_02", lesson_02::port_cards::CARDS),
        ("lesson_03", lesson_03::port_cards::CARDS),
        ("lesson_04", lesson_04::port_cards::CARDS),
    ];
    let mut out = Vec::new();
    for (lesson, cards) in lessons {
        out.extend(cards.iter().map(|&c| (lesson, c)));
    }
    out
}

/// The numbers written in `src` between `start` and the first `end` after
/// it. A number is a literal, not a digit of a name (`vec2`, `f32`).
fn wgsl_numbers(src: &str, start: &str, end: &str) -> Vec<f64> {
    let from = src
        .find(start)
        .unwrap_or_else(|| panic!("the shader has no {start:?}"))
        + start.len();
    let to = from + src[from..].find(end).expect("the end of the list");
    let text = &src[from..to];
    let chars: Vec<char> = text.chars().collect();
    let (mut out, mut i) = (Vec::new(), 0);
    while i < chars.len() {
        let prev_is_name = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        let starts = chars[i].is_ascii_digit()
            || (chars[i] == '-' && chars.get(i + 1).is_some_and(|c| c.is_ascii_digit()));
        if starts && !prev_is_name {
            let j = (i + 1..chars.len())
                .find(|&j| !(chars[j].is_ascii_digit() || chars[j] == '.'))
                .unwrap_or(chars.len());
            let token: String = chars[i..j].iter().collect();
            out.push(token.parse().expect("a number"));
            i = j;
        } else {
            // Skip the rest of a name, so its digits are not read.
            i += 1;
            while prev_is_name && i < chars.len() && chars[i].is_alphanumeric() {
                i += 1;
            }
        }
    }
    out
}

/// `text` with runs of white space as one space.
fn squash(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The text of the WGSL function `name`, to the next `// ANCHOR_END`.
fn wgsl_fn<'a>(src: &'a str, name: &str) -> &'a str {
    let from = src
        .find(&format!("fn {name}("))
        .unwrap_or_else(|| panic!("the shader has no fn {name}"));
    let to = from + src[from..].find("// ANCHOR_END").expect("the anchor's end");
    &src[from..to]
}

/// `card`'s number `name`, as the port's f32.
fn num32(card: &PortCard, name: &str) -> f32 {
    card.num(name) as f32
}

#[test]
fn every_card_is_whole() {
    for (lesson, card) in all_cards() {
        let problems = card.problems();
        assert!(problems.is_empty(), "{lesson}: {problems:?}");
        for c in card.constants {
            // A citation a reader can follow: file@commit7:lines.
            assert!(card.cite(c).contains('@'), "{lesson} {}", card.variant);
        }
    }
    // One card per peer variant, each named once.
    let mut names: Vec<_> = all_cards().iter().map(|(_, c)| c.variant).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), 9, "{names:?}");
}

// ---------------------------------------------------------------- lesson 02

/// LearnOpenGL's bias: `max(0.05 * (1.0 - N·L), 0.005)` of depth, nothing else.
fn check_learnopengl_bias(card: &PortCard) {
    let b = ShadowBias::LEARNOPENGL;
    let slope = "bias: the 0.05 of 0.05 * (1.0 - dot(normal, lightDir))";
    assert_eq!(b.depth_slope, num32(card, slope), "{}", card.variant);
    assert_eq!(b.depth, num32(card, "bias: the 0.005 of max(..., 0.005)"));
    let formula = card.text("bias");
    assert!(
        formula.contains("0.05 *") && formula.contains("0.005)"),
        "{formula}"
    );
    assert_eq!(
        ShadowBias {
            depth: 0.0,
            depth_slope: 0.0,
            ..b
        },
        ShadowBias::NONE,
        "LearnOpenGL's port moves the receiver: its source does not"
    );
    // Its map is lesson 01's Depth32Float of SHADOW_WIDTH² (checked on a
    // run below); nearest taps.
    assert_eq!(
        card.text("GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER"),
        "GL_NEAREST"
    );
}

/// The wgpu example's shadow pass: its bias state, culling and map.
fn check_wgpu_shadow_pass(card: &PortCard) {
    let s = SlopeScaledBias::WGPU_EXAMPLE;
    assert_eq!(s.constant as f64, card.num("DepthBiasState::constant"));
    assert_eq!(s.slope_scale, num32(card, "DepthBiasState::slope_scale"));
    // A clamp of 0 is no clamp, in the source and in the port.
    assert_eq!(s.clamp_texels, num32(card, "DepthBiasState::clamp"));
    assert_eq!(WGPU_EXAMPLE_MAP_SIZE as f64, card.num("SHADOW_SIZE"));
    assert_eq!(format!("{SHADOW_FORMAT:?}"), card.text("SHADOW_FORMAT"));
    let cull = card.text("shadow pass cull_mode");
    assert_eq!(cull, format!("Some(wgpu::Face::{WGPU_EXAMPLE_CULL:?})"));
}

/// Bevy's directional biases: world units towards the light, texels × √2
/// along the normal, on its map size.
fn check_bevy_bias(card: &PortCard) {
    let b = ShadowBias::BEVY;
    let depth = num32(card, "DirectionalLight::DEFAULT_SHADOW_DEPTH_BIAS");
    assert_eq!(b.toward_light_world, depth);
    assert!(card
        .text("shadow_normal_bias")
        .ends_with("* std::f32::consts::SQRT_2"));
    // In f32, as Bevy's `extract_lights` multiplies.
    let normal = num32(card, "DirectionalLight::DEFAULT_SHADOW_NORMAL_BIAS");
    assert_eq!(b.normal_flat, normal * std::f32::consts::SQRT_2);
    assert_eq!(
        ShadowBias {
            toward_light_world: 0.0,
            normal_flat: 0.0,
            ..b
        },
        ShadowBias::NONE,
        "Bevy's port subtracts depth or moves along the light's texels: its source does not"
    );
    assert_eq!(
        BEVY_MAP_SIZE as f64,
        card.num("DirectionalLightShadowMap::default().size")
    );
    assert_eq!(
        format!("{SHADOW_FORMAT:?}"),
        card.text("CORE_3D_DEPTH_FORMAT")
    );
}

#[test]
fn lesson_02_ports_hold_their_cards_values() {
    use lesson_02::port_cards::{BEVY_BIAS, LEARNOPENGL, WGPU_EXAMPLE};
    check_learnopengl_bias(&LEARNOPENGL);
    assert_eq!(LEARNOPENGL.num(TAPS.name), 1.0);
    check_wgpu_shadow_pass(&WGPU_EXAMPLE);
    check_bevy_bias(&BEVY_BIAS);
}

// ---------------------------------------------------------------- lesson 03

/// The tap offsets of an N×N grid as `pcf_grid` (pcf.wgsl) lays them out:
/// (x, y) for x, y in −N/2 ..= N/2, in texels; sorted.
fn grid_offsets(filter: Filter) -> Vec<(i64, i64)> {
    let Filter::Grid { n, .. } = filter else {
        panic!("not a grid: {filter:?}");
    };
    let r = (n / 2) as i64;
    let mut o: Vec<_> = (-r..=r)
        .flat_map(|x| (-r..=r).map(move |y| (x, y)))
        .collect();
    o.sort_unstable();
    o
}

#[test]
fn lesson_03_ports_hold_their_cards_values() {
    use lesson_03::port_cards::{BEVY, LEARNOPENGL_PCF, WGPU_EXAMPLE_HW2X2};

    // LearnOpenGL: its bias, and its 3×3 one texel apart, every tap
    // compared with the centre's depth (no receiver plane).
    check_learnopengl_bias(&LEARNOPENGL_PCF);
    let grid = pcf::LEARNOPENGL_3X3;
    let mut card: Vec<(i64, i64)> = LEARNOPENGL_PCF
        .list("PCF offsets (x, y)")
        .chunks(2)
        .map(|p| (p[0] as i64, p[1] as i64))
        .collect();
    card.sort_unstable();
    assert_eq!(grid_offsets(grid), card);
    assert!(matches!(
        grid,
        Filter::Grid {
            receiver_plane: false,
            ..
        }
    ));
    assert!(LEARNOPENGL_PCF.text("shadow").contains("centre's depth"));
    assert_eq!(grid.taps().0 as f64, LEARNOPENGL_PCF.num(TAPS.name));
    assert_eq!(grid.sampler(), wgpu::FilterMode::Nearest);
    // pcf_grid's offsets are what grid_offsets says: one texel apart.
    let body = squash(wgsl_fn(PCF_WGSL, "pcf_grid"));
    for line in [
        "let texel = 1.0 / f32(textureDimensions(shadow_map).x);",
        "let r = n / 2;",
        "for (var y = -r; y <= r; y++) {",
        "for (var x = -r; x <= r; x++) {",
        "let o = vec2<f32>(f32(x), f32(y)) * texel;",
    ] {
        assert!(body.contains(line), "pcf_grid lost {line:?}");
    }

    // The wgpu example: its shadow pass, and its linear comparison sampler.
    check_wgpu_shadow_pass(&WGPU_EXAMPLE_HW2X2);
    let hw = pcf::WGPU_EXAMPLE_HW2X2;
    assert!(matches!(hw, Filter::Hardware2x2));
    assert_eq!(hw.sampler(), wgpu::FilterMode::Linear);
    assert!(WGPU_EXAMPLE_HW2X2
        .text("shadow_sampler")
        .contains("Linear, compare LessEqual"));
    assert_eq!(hw.taps().0 as f64, WGPU_EXAMPLE_HW2X2.num(TAPS.name));

    // Bevy: its biases, and Castaño's filter as Bevy writes it.
    check_bevy_bias(&BEVY);
    let gauss = pcf::BEVY_GAUSSIAN;
    assert!(matches!(gauss, Filter::Castano13));
    assert_eq!(BEVY.text("ShadowFilteringMethod::default()"), "Gaussian");
    assert_eq!(gauss.taps().0 as f64, BEVY.num(TAPS.name));
    assert_eq!(gauss.sampler(), wgpu::FilterMode::Linear);
    let body = squash(wgsl_fn(PCF_WGSL, "pcf_castano13"));
    for name in [
        "base_uv",
        "s, t",
        "uw0, uw1, uw2",
        "u0, u1, u2",
        "vw0, vw1, vw2",
        "v0, v1, v2",
        "return",
    ] {
        for statement in BEVY.text(name).split(';').map(str::trim) {
            if !statement.is_empty() {
                let line = format!("{};", squash(statement));
                assert!(
                    body.contains(&line),
                    "pcf_castano13 has no {line:?} ({name})"
                );
            }
        }
    }
}

// ---------------------------------------------------------------- lesson 04

#[test]
fn lesson_04_ports_hold_their_cards_values() {
    use lesson_04::port_cards::{BEVY_POINT, LEARNOPENGL_1TAP, LEARNOPENGL_PCF20};

    // LearnOpenGL, both versions: its cube, clipped at its planes, of
    // distance / far_plane, nearest.
    for (port, card) in [
        (peers::LEARNOPENGL_1TAP, LEARNOPENGL_1TAP),
        (peers::LEARNOPENGL_PCF20, LEARNOPENGL_PCF20),
    ] {
        let v = card.variant;
        assert_eq!(port.size as f64, card.num("SHADOW_WIDTH"), "{v}");
        assert_eq!(port.near, card.num("near_plane"), "{v}");
        assert_eq!(port.far, Some(card.num("far_plane")), "{v}");
        assert!(
            port.clipped && card.text("shadowProj").contains("clipped"),
            "{v}"
        );
        assert_eq!(port.storage, Storage::Linear, "{v}");
        assert!(card.text("gl_FragDepth").ends_with("/ far_plane"), "{v}");
        assert!(!port.lookup.linear(), "{v}");
        assert_eq!(
            card.text("GL_TEXTURE_MAG_FILTER, GL_TEXTURE_MIN_FILTER"),
            "GL_NEAREST"
        );
        // Past far_plane LearnOpenGL compares with the cleared 1.0 (shadow).
        assert!(!port.clamp_range, "{v}");
        assert_eq!(card.text("diff"), "max(dot(lightDir, normal), 0.0)");
    }
    let one = peers::LEARNOPENGL_1TAP;
    assert_eq!(one.bias_world, num32(&LEARNOPENGL_1TAP, "bias"));
    // The lesson's one-tap lookup (`visibility`), with only that bias.
    assert_eq!((one.lookup, one.lookup.taps()), (Peer::None, None));
    assert_eq!(LEARNOPENGL_1TAP.num(TAPS.name), 1.0);

    let soft = peers::LEARNOPENGL_PCF20;
    assert_eq!(soft.bias_world, num32(&LEARNOPENGL_PCF20, "bias"));
    assert_eq!(soft.lookup, Peer::LearnOpenGlDisk);
    assert_eq!(
        soft.lookup.taps(),
        Some(LEARNOPENGL_PCF20.num("samples") as u64)
    );
    let divisor = LEARNOPENGL_PCF20.num("diskRadius divisor");
    assert!(LEARNOPENGL_PCF20
        .text("diskRadius")
        .ends_with(&format!("/ {divisor:.1}")));
    assert_eq!(soft.lookup.params(soft.size).1, 1.0 / divisor as f32);
    let disk = wgsl_numbers(
        PEERS_WGSL,
        "const GRID_SAMPLING_DISK = array<vec3<f32>, 20>(",
        ");",
    );
    assert_eq!(disk, LEARNOPENGL_PCF20.list("gridSamplingDisk"));

    // Bevy: its cube (1024², Depth32Float, near 0.1 clipped), its biases,
    // its Gaussian's positions, weights and scale, its flipped lookup.
    let bevy = peers::BEVY_POINT;
    assert_eq!(
        bevy.size as f64,
        BEVY_POINT.num("PointLightShadowMap::default().size")
    );
    assert_eq!(bevy.near, BEVY_POINT.num("POINT_LIGHT_NEAR_Z"));
    assert!(bevy.clipped);
    assert_eq!(bevy.storage, Storage::Depth);
    assert_eq!(
        format!("{CUBE_FORMAT:?}"),
        BEVY_POINT.text("CORE_3D_DEPTH_FORMAT")
    );
    let depth_bias = num32(&BEVY_POINT, "PointLight::DEFAULT_SHADOW_DEPTH_BIAS");
    assert_eq!(bevy.bias_world, depth_bias);
    let normal = BEVY_POINT.num("PointLight::DEFAULT_SHADOW_NORMAL_BIAS");
    assert_eq!(BEVY_POINT_NORMAL_BIAS, normal as f32);
    // "shadow_normal_bias * point_light_texel_size * SQRT_2", the texel
    // size 2 / N: what the lit pass scales by the major-axis distance.
    assert!(BEVY_POINT
        .text("shadow_normal_bias")
        .ends_with("* std::f32::consts::SQRT_2"));
    assert_eq!(
        BEVY_POINT.text("point_light_texel_size"),
        "2.0 / point_light_shadow_map.size"
    );
    let scale = normal * (2.0 / bevy.size as f64) * SQRT_2;
    assert!((bevy.lookup.params(bevy.size).1 as f64 - scale).abs() < 1e-9);
    assert_eq!(bevy.lookup, Peer::BevyPoint);
    assert_eq!(bevy.lookup.taps(), Some(BEVY_POINT.num(TAPS.name) as u64));
    assert!(bevy.lookup.linear() && BEVY_POINT.text("point_light_sampler").starts_with("Linear"));
    let positions = wgsl_numbers(
        PEERS_WGSL,
        "const D3D_POSITIONS = array<vec2<f32>, 8>(",
        ");",
    );
    assert_eq!(positions, BEVY_POINT.list("D3D_SAMPLE_POINT_POSITIONS"));
    let coeffs = wgsl_numbers(PEERS_WGSL, "const D3D_COEFFS = array<f32, 8>(", ");");
    assert_eq!(coeffs, BEVY_POINT.list("D3D_SAMPLE_POINT_COEFFS"));
    let point_scale = wgsl_numbers(PEERS_WGSL, "const POINT_SHADOW_SCALE: f32 =", ";");
    assert_eq!(point_scale, [BEVY_POINT.num("POINT_SHADOW_SCALE")]);
    let flip = wgsl_numbers(PEERS_WGSL, "let flip_z = vec3<f32>(", ");");
    assert_eq!(flip, BEVY_POINT.list("flip_z"));
    // Bevy's orthonormalize: x = normalize(cross(z, up)), y = cross(z, x).
    let body = squash(wgsl_fn(PEERS_WGSL, "bevy_point"));
    for line in [
        "let bx = normalize(cross(bz, up));",
        "let by = cross(bz, bx);",
    ] {
        assert!(body.contains(line), "bevy_point lost {line:?}");
    }
    assert!(BEVY_POINT
        .text("orthonormalize")
        .contains("x = normalize(cross(z, up)); y = cross(z, x)"));
}

// ------------------------------------------------------------- on a device

/// What the sources call their map's size.
const MAP_SIZE_NAMES: [&str; 3] = [
    "SHADOW_WIDTH",
    "SHADOW_SIZE",
    "DirectionalLightShadowMap::default().size",
];

/// `--variant` arguments for `cards`, after a small frame.
fn peer_args(cards: &[PortCard]) -> Vec<&'static str> {
    let mut a = vec!["--width", "160", "--height", "90", "--frames", "1"];
    for c in cards {
        a.extend(["--variant", c.variant]);
    }
    a
}

/// What main.rs wires each port to, as the report counts it: the map size
/// (lessons 02, 03), the taps, and lesson 04's near plane and clipping.
#[test]
fn each_port_runs_with_its_cards_map_taps_and_planes() {
    let bins = [
        (
            env!("CARGO_BIN_EXE_lesson_02"),
            lesson_02::port_cards::CARDS,
        ),
        (
            env!("CARGO_BIN_EXE_lesson_03"),
            lesson_03::port_cards::CARDS,
        ),
    ];
    for (bin, cards) in bins {
        let Some(run) = support::run_lesson(bin, "port_cards_2d", &peer_args(cards)) else {
            return;
        };
        for c in cards {
            let size = MAP_SIZE_NAMES
                .into_iter()
                .find(|n| c.constants.iter().any(|k| k.name == *n))
                .map(|n| c.num(n))
                .expect("a map size on the card");
            let counted = support::counter(&run.report, c.variant, SHADOW_MAP_SIZE.name);
            assert_eq!(counted as f64, size, "{}", c.variant);
            let taps = support::counter(&run.report, c.variant, FILTER_TAPS_PER_PIXEL.name);
            let on_card = c.constants.iter().any(|k| k.name == TAPS.name);
            // Lesson 02's Bevy card has no taps: its filter is lesson 03's.
            if on_card {
                assert_eq!(taps as f64, c.num(TAPS.name), "{}", c.variant);
            }
        }
    }
    let cards = lesson_04::port_cards::CARDS;
    let bin = env!("CARGO_BIN_EXE_lesson_04");
    let Some(run) = support::run_lesson(bin, "port_cards_cube", &peer_args(cards)) else {
        return;
    };
    let near = |c: &PortCard| {
        let name = ["near_plane", "POINT_LIGHT_NEAR_Z"]
            .into_iter()
            .find(|n| c.constants.iter().any(|k| k.name == *n))
            .expect("a near plane on the card");
        c.num(name)
    };
    let taps = |c: &PortCard| match c.constants.iter().any(|k| k.name == "samples") {
        true => c.num("samples"),
        false => c.num(TAPS.name),
    };
    for c in cards {
        let count = |k| support::counter(&run.report, c.variant, k);
        assert_eq!(
            count(NEAR_PLANE_MM.name) as f64,
            near(c) * 1000.0,
            "{}",
            c.variant
        );
        assert_eq!(
            count(UNCLIPPED_DEPTH.name),
            0,
            "{}: its source clips",
            c.variant
        );
        assert_eq!(
            count(FILTER_TAPS_PER_PIXEL.name) as f64,
            taps(c),
            "{}",
            c.variant
        );
    }
}

// ------------------------------------------------------------ the book

/// The chapters include `generated/ports/lesson_NN.md`, made from the
/// cards. The book's generator writes them in its own layout; whatever the
/// layout, each must name every card's variant, the files it was read at
/// (file and commit) and every departure, what and why. With
/// `WORKBOOK_WRITE_PORT_TABLES=1` this writes them first, with
/// [`departures_table`].
#[test]
fn the_books_departure_tables_are_the_cards() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let lessons: [(&str, &[PortCard]); 3] = [
        ("lesson_02", lesson_02::port_cards::CARDS),
        ("lesson_03", lesson_03::port_cards::CARDS),
        ("lesson_04", lesson_04::port_cards::CARDS),
    ];
    let write = std::env::var("WORKBOOK_WRITE_PORT_TABLES").is_ok_and(|v| v == "1");
    let cell = |t: &str| t.replace('|', "\\|");
    for (lesson, cards) in lessons {
        let path = root.join(format!("book/src/generated/ports/{lesson}.md"));
        if write {
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, departures_table(cards)).unwrap();
        }
        let table =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let stale = format!(
            "{} is not its cards' table: WORKBOOK_WRITE_PORT_TABLES=1 cargo test --release --test port_cards, or the book's generator",
            path.display()
        );
        for c in cards {
            assert!(table.contains(&format!("`{}`", c.variant)), "{stale}");
            for s in c.sources {
                let at = [s.file, &s.commit[..7]];
                assert!(at.iter().all(|t| table.contains(t)), "{stale}: {at:?}");
            }
            for d in c.departures {
                assert!(table.contains(&cell(d.what)), "{stale}: {}", d.what);
                assert!(table.contains(&cell(d.why)), "{stale}: {}", d.why);
            }
        }
    }
}
