//! Property tests ("fuzzing", issue 49) of the three parsers a user's file
//! reaches: the scene format (`Scene::parse`, `Scene::load`), OBJ files
//! (`parse_obj`, `load_obj`) and the chapters' exercise specs
//! (`grade/spec.rs`, `Spec::load`).
//!
//! For every input, each parser
//! 1. neither panics nor hangs (each call runs on its own thread, and an
//!    answer later than [`LIMIT`] fails the test);
//! 2. refuses in one line that starts with the file and names a line or a
//!    field ([`parsers`] lists what each parser may name instead);
//! 3. or accepts something sane: finite numbers within the format's
//!    limits, meshes whose indices are in range.
//!
//! The inputs are the repository's own files mutated ([`mutate`]), soups
//! of their lines, and random text: a fixed number per parser, drawn from
//! proptest's ChaCha generator with its fixed seed, so that every run (CI
//! on Vulkan and GL alike) tries the same inputs. A failure prints the
//! input, shrunk to few edits, and writes it to `target/fuzz/`; such an
//! input belongs in `tests/fuzz_corpus/<parser>/`, which
//! [`corpus_inputs_stay_fixed`] reads every run.
//!
//! Each test writes its counts, one line per parser, to
//! `target/fuzz/summary.txt` (cargo shows a passing test's output only
//! with `--nocapture`), and asserts them: the number tried (which the
//! test's name also says), and that both acceptances and refusals were
//! reached, so property 3 is not vacuous. Every refusal of a run is in
//! `target/fuzz/<parser>-refusals.txt`, for a reader of the messages.
//!
//! A longer search by hand: `WORKBOOK_FUZZ_SEED=n` draws from another
//! fixed seed, `WORKBOOK_FUZZ_SCALE=k` tries k times as many inputs. CI
//! sets neither.

#[allow(dead_code)]
#[path = "../grade/spec.rs"]
mod spec;

#[path = "fuzz_inputs/mutate.rs"]
mod mutate;
#[path = "fuzz_inputs/parsers.rs"]
mod parsers;

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};

use mutate::{Seeds, Syntax};
use parsers::{Verdict, Via};

/// The longest one call may take.
const LIMIT: Duration = Duration::from_secs(2);

/// How a call that did not answer in time is reported.
const HANG: &str = "no answer within";

/// A parser under test.
struct Parser {
    /// Its name in messages and in the summary.
    label: &'static str,
    /// Its folder in `tests/fuzz_corpus/`, and its seeds' extension.
    dir: &'static str,
    ext: &'static str,
    /// How many inputs a run tries.
    cases: u32,
}

const SCENE: Parser = Parser {
    label: "scene format",
    dir: "scene",
    ext: "toml",
    cases: 5000,
};
const OBJ: Parser = Parser {
    label: "OBJ",
    dir: "obj",
    ext: "obj",
    cases: 8000,
};
const SPEC: Parser = Parser {
    label: "exercise specs",
    dir: "spec",
    ext: "toml",
    cases: 4000,
};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scenes() -> PathBuf {
    root().join("scenes")
}

/// `target/fuzz/`: the summary, and an input that failed.
fn out_dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .join("fuzz");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The files of `dir` ending in `.ext`, sorted, with their bytes.
fn files(dir: &Path, ext: &str) -> Vec<(String, Vec<u8>)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    paths.sort();
    let rel = |p: &Path| p.strip_prefix(root()).unwrap_or(p).display().to_string();
    paths
        .iter()
        .map(|p| (rel(p), std::fs::read(p).unwrap()))
        .collect()
}

/// Small OBJ texts in the forms the format allows: quads, polygons,
/// `v/vt/vn` faces, negative indices, objects and groups, `w` and colours.
const OBJ_TEXTS: &[&str] = &[
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvn 0 1 0\nf 1//1 2//1 3//1 4//1\n",
    "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 3 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 1\nvt 0 1\nf 1/1 2/2 3/3 4/4 5/5\n",
    "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1/1/1 2/2/2 3/3/3\n",
    "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\ng b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\ns off\n",
    "# colours\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 0 0 1 1 1 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
    "mtllib none.mtl\no a\nusemtl red\nv -1e5 0 0\nv 1e5 0 0\nv 0 1e-3 0\nf 1 2 3\nl 1 2\np 1\n",
];

impl Parser {
    /// The real files this parser reads, as the mutations' starting points.
    fn seeds(&self) -> Seeds {
        match self.dir {
            "scene" => {
                let mut f = files(&scenes(), "toml");
                f.extend(files(&root().join("tests/hidden_scenes"), "toml"));
                // Every parse builds its meshes anew, and the dense built-ins
                // are tens of thousands of triangles: a mutation of their
                // scene tries the same with a knot or a sphere.
                for (_, text) in &mut f {
                    let t = String::from_utf8_lossy(text)
                        .replace("\"dense_knot\"", "\"knot\"")
                        .replace("\"holed_sphere\"", "\"sphere\"");
                    *text = t.into_bytes();
                }
                Seeds::new(Syntax::Toml, f)
            }
            "obj" => {
                let mut f: Vec<(String, Vec<u8>)> = OBJ_TEXTS
                    .iter()
                    .enumerate()
                    .map(|(i, t)| (format!("OBJ text {i}"), t.as_bytes().to_vec()))
                    .collect();
                let small = |(_, b): &(String, Vec<u8>)| b.len() < 4096;
                f.extend(files(&scenes(), "obj").into_iter().filter(small));
                f.extend(
                    files(&root().join("assets"), "obj")
                        .into_iter()
                        .filter(small),
                );
                Seeds::new(Syntax::Obj, f)
            }
            _ => {
                let mut f = Vec::new();
                for lesson in 1..=10 {
                    let path = root().join(format!("lessons/lesson_{lesson:02}/exercises.toml"));
                    let rel = format!("lessons/lesson_{lesson:02}/exercises.toml");
                    f.push((rel, std::fs::read(path).unwrap()));
                }
                Seeds::new(Syntax::Toml, f)
            }
        }
    }

    /// One call on `bytes`: through the text entry point (`name` in
    /// messages), or, for bytes that are not UTF-8, for every fourth
    /// input, and for specs always, through the file entry point, with
    /// the bytes written to `work`.
    fn call(&self, bytes: Vec<u8>, n: u32, work: &Path) -> (Verdict, bool) {
        let text = String::from_utf8(bytes.clone())
            .ok()
            .filter(|_| !n.is_multiple_of(4));
        let file = work.join(format!("input.{}", self.ext));
        if text.is_none() || self.dir == "spec" {
            std::fs::write(&file, &bytes).unwrap();
        }
        let (dir, scenes) = (self.dir, scenes());
        let name = format!("fuzz.{}", self.ext);
        let verdict = bounded(move || match (dir, text) {
            ("spec", _) => parsers::spec(&file, &scenes),
            ("scene", Some(t)) => parsers::scene(Via::Text(&t, &name), &scenes),
            ("scene", None) => parsers::scene(Via::File(&file), &scenes),
            (_, Some(t)) => parsers::obj(Via::Text(&t, &name)),
            (_, None) => parsers::obj(Via::File(&file)),
        });
        let via_file =
            String::from_utf8(bytes).is_err() || n.is_multiple_of(4) || self.dir == "spec";
        (verdict, via_file)
    }

    /// One call on a corpus file: a scene as text (named by its path, its
    /// OBJ paths in `scenes/`, as in [`Parser::call`]) when it is UTF-8,
    /// else through the file; OBJ files and specs through the file.
    fn call_file(&self, path: &Path) -> Verdict {
        let (dir, path, scenes) = (self.dir, path.to_path_buf(), scenes());
        bounded(move || {
            let text = std::fs::read(&path)
                .ok()
                .and_then(|b| String::from_utf8(b).ok());
            let name = path.display().to_string();
            match (dir, text) {
                ("spec", _) => parsers::spec(&path, &scenes),
                ("scene", Some(t)) => parsers::scene(Via::Text(&t, &name), &scenes),
                ("scene", None) => parsers::scene(Via::File(&path), &scenes),
                _ => parsers::obj(Via::File(&path)),
            }
        })
    }
}

/// Runs `f` on its own thread: a panic, or no answer within [`LIMIT`], is
/// a broken property (a hung thread is left behind; the test fails).
fn bounded(f: impl FnOnce() -> Verdict + Send + 'static) -> Verdict {
    let (tx, rx) = mpsc::channel();
    let start = Instant::now();
    std::thread::spawn(move || {
        let verdict =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).unwrap_or_else(|p| {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                Verdict::Broken(format!("panicked: {msg}"))
            });
        let _ = tx.send(verdict);
    });
    match rx.recv_timeout(LIMIT) {
        Ok(_) if start.elapsed() > LIMIT => {
            Verdict::Broken(format!("took {:.1} s", start.elapsed().as_secs_f64()))
        }
        Ok(v) => v,
        Err(_) => Verdict::Broken(format!("{HANG} {} s (a hang?)", LIMIT.as_secs())),
    }
}

/// `summary.txt` is shared by the tests of this file, which run at once.
static SUMMARY: Mutex<()> = Mutex::new(());

/// Puts `line` (`fuzz: <label>: ...`) in `target/fuzz/summary.txt`, in
/// place of the line of an earlier run, and on stderr.
fn summarise(label: &str, line: &str) {
    eprintln!("{line}");
    let _guard = SUMMARY.lock().unwrap_or_else(|e| e.into_inner());
    let path = out_dir().join("summary.txt");
    let old = std::fs::read_to_string(&path).unwrap_or_default();
    let order = [SCENE.label, OBJ.label, SPEC.label, "corpus"];
    let mut lines: Vec<String> = old
        .lines()
        .filter(|l| !l.starts_with(&format!("fuzz: {label}:")))
        .map(str::to_string)
        .chain([line.to_string()])
        .collect();
    let rank = |l: &String| {
        order
            .iter()
            .position(|o| l.starts_with(&format!("fuzz: {o}:")))
    };
    lines.sort_by_key(rank);
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
}

/// The counts of one run.
#[derive(Default)]
struct Tally {
    tried: Cell<u32>,
    accepted: Cell<u32>,
    refused: Cell<u32>,
    via_file: Cell<u32>,
}

fn bump(c: &Cell<u32>) {
    c.set(c.get() + 1);
}

/// An unsigned number from the environment, if set.
fn env_number(name: &str) -> Option<u64> {
    let v = std::env::var(name).ok()?;
    Some(
        v.parse()
            .unwrap_or_else(|_| panic!("{name}={v:?}: expected a whole number")),
    )
}

/// The generator: proptest's fixed ChaCha seed, or with
/// `WORKBOOK_FUZZ_SEED=n` (a longer search by hand) another fixed one.
fn rng() -> (TestRng, String) {
    match env_number("WORKBOOK_FUZZ_SEED") {
        None => (
            TestRng::deterministic_rng(RngAlgorithm::ChaCha),
            "fixed seed".into(),
        ),
        Some(n) => {
            let mut seed = [0u8; 32];
            seed[..8].copy_from_slice(&n.to_le_bytes());
            (
                TestRng::from_seed(RngAlgorithm::ChaCha, &seed),
                format!("seed {n}"),
            )
        }
    }
}

/// How many inputs a run tries: `p.cases`, times `WORKBOOK_FUZZ_SCALE`.
fn cases(p: &Parser) -> u32 {
    let scale = env_number("WORKBOOK_FUZZ_SCALE").unwrap_or(1);
    u32::try_from(u64::from(p.cases) * scale).expect("WORKBOOK_FUZZ_SCALE: too large")
}

/// Fuzzes one parser with its fixed number of inputs; returns the counts.
fn fuzz(p: &Parser) -> Tally {
    // The test's name says how many inputs it tries (libtest names the
    // thread after the test, unless it runs on the main thread).
    let me = std::thread::current().name().unwrap_or("main").to_string();
    assert!(
        me == "main" || me.contains(&format!("_{}_", p.cases)),
        "{me}: {} inputs",
        p.cases
    );
    let seeds = Arc::new(p.seeds());
    let work = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fuzz_inputs")
        .join(p.dir);
    std::fs::create_dir_all(&work).unwrap();
    // The seeds themselves are valid files: if one is refused, the
    // mutations start from nothing real.
    for (name, bytes) in &seeds.files {
        if let (Verdict::Refused(e) | Verdict::Broken(e), _) = p.call(bytes.clone(), 1, &work) {
            panic!("fuzz: {}: the seed {name} is refused: {e}", p.label);
        }
    }
    let config = Config {
        cases: cases(p),
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        max_shrink_iters: 2000,
        max_shrink_time: 60_000,
        ..Config::default()
    };
    let (rng, seed) = rng();
    let mut runner = TestRunner::new_with_rng(config, rng);
    let tally = Tally::default();
    // Every refusal, one a line: what a reader of the messages reviews.
    let refusals = RefCell::new(String::new());
    // After a hang, shrinking would leave a spinning thread per try: the
    // input that hung is reported as it is.
    let hung = Cell::new(false);
    let start = Instant::now();
    let result = runner.run(&mutate::cases(seeds), |case| {
        if hung.get() {
            return Ok(());
        }
        let (verdict, via_file) = p.call(case.bytes, tally.tried.get(), &work);
        bump(&tally.tried);
        if via_file {
            bump(&tally.via_file);
        }
        match verdict {
            Verdict::Accepted => bump(&tally.accepted),
            Verdict::Refused(msg) => {
                bump(&tally.refused);
                refusals.borrow_mut().push_str(&(msg + "\n"));
            }
            Verdict::Broken(why) => {
                hung.set(why.starts_with(HANG));
                return Err(TestCaseError::fail(why));
            }
        }
        Ok(())
    });
    if let Err(e) = result {
        let kept = match &e {
            TestError::Fail(_, case) => {
                let path = out_dir().join(format!("{}-failure.{}", p.dir, p.ext));
                std::fs::write(&path, &case.bytes).unwrap();
                let dir = p.dir;
                format!(
                    "; the input is in {} (add it to tests/fuzz_corpus/{dir}/)",
                    path.display()
                )
            }
            TestError::Abort(_) => String::new(),
        };
        let line = format!("fuzz: {}: FAILED ({seed}): {e}{kept}", p.label);
        summarise(p.label, &line.replace('\n', " "));
        panic!("{line}");
    }
    let log = out_dir().join(format!("{}-refusals.txt", p.dir));
    std::fs::write(log, refusals.take()).unwrap();
    let (tried, accepted, refused) = (tally.tried.get(), tally.accepted.get(), tally.refused.get());
    summarise(
        p.label,
        &format!(
            "fuzz: {}: {tried} inputs ({seed}), 0 panics, 0 hangs, {accepted} accepted and sane, {refused} refused in one line naming the file and a line or field; {} through the file entry point; {:.1} s",
            p.label,
            tally.via_file.get(),
            start.elapsed().as_secs_f64()
        ),
    );
    assert_eq!(tried, cases(p), "{}: every input tried once", p.label);
    assert_eq!(accepted + refused, tried);
    tally
}

/// Both answers are reached often enough that each property is tested:
/// at least `share` of the inputs accepted, and as many refused.
fn assert_mixed(p: &Parser, t: &Tally, share: f64) {
    let least = (share * f64::from(cases(p))) as u32;
    let (a, r) = (t.accepted.get(), t.refused.get());
    assert!(
        a >= least && r >= least,
        "{}: {a} accepted, {r} refused; want {least} each at least",
        p.label
    );
    assert!(
        t.via_file.get() >= cases(p) / 8,
        "{}: the file entry point reached",
        p.label
    );
}

// The test names carry the number of inputs (`Parser::cases`), so that
// cargo's own output says how many were tried.

#[test]
fn scene_format_5000_inputs() {
    let t = fuzz(&SCENE);
    assert_mixed(&SCENE, &t, 0.05);
}

#[test]
fn obj_8000_inputs() {
    let t = fuzz(&OBJ);
    assert_mixed(&OBJ, &t, 0.05);
}

#[test]
fn exercise_specs_4000_inputs() {
    let t = fuzz(&SPEC);
    assert_mixed(&SPEC, &t, 0.05);
}

/// Every input that once broke a property (`tests/fuzz_corpus/<parser>/`)
/// is refused in one line or accepted sane, as in the fuzz tests. All are
/// read before the test fails, so that it names every one that broke.
#[test]
fn corpus_inputs_stay_fixed() {
    let (mut counts, mut broken) = (Vec::new(), Vec::new());
    for p in [&SCENE, &OBJ, &SPEC] {
        let dir = root().join("tests/fuzz_corpus").join(p.dir);
        let found = files(&dir, p.ext);
        for (name, _) in &found {
            if let Verdict::Broken(why) = p.call_file(&root().join(name)) {
                broken.push(format!("{name}: {why}"));
            }
        }
        counts.push(format!("{} {}", p.dir, found.len()));
    }
    let counts = counts.join(", ");
    let line = match broken.len() {
        0 => format!("fuzz: corpus: {counts} files, each refused in one line or accepted sane"),
        n => format!("fuzz: corpus: {counts} files, FAILED: {n} broken"),
    };
    summarise("corpus", &line);
    assert!(
        broken.is_empty(),
        "fuzz corpus, {} broken:\n{}",
        broken.len(),
        broken.join("\n")
    );
}
