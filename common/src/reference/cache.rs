//! A cache of references on disk, for CI: `WORKBOOK_REFERENCE_CACHE=<dir>`.
//!
//! CI runs the same lesson on the same scene many times: the snapshot test,
//! the book's drift test, the exercises, the grader, and all of it again on
//! GL. The reference of a view depends only on the scene's triangles, which
//! objects cast, its lights, the camera and the image's size, and on the
//! code that traces it; so a reference that took long enough to be worth it
//! is written to the folder the variable names, and read back the next time
//! the same executable asks for the same view.
//!
//! The key is a hash of everything the reference reads: every world
//! triangle and its object, which objects cast, the lights, the scene's
//! bounds and origin, the matrix, the size, the area sampling, and the
//! executable itself (its path, length and modification time), so a
//! rebuilt binary never reads a reference its old code made. Unset (the
//! default, and always in `workbook book`), nothing is read or written.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};

use crate::reference::area::AreaSampling;
use crate::reference::{try_render_reference_with, PixelHit, Reference};
use crate::scene::Scene;

/// The variable that names the cache's folder.
pub const VAR: &str = "WORKBOOK_REFERENCE_CACHE";

/// A reference that took less than this is traced again rather than read:
/// reading one back costs a few tens of milliseconds.
const WORTH_MS: f64 = 150.0;

/// The cache folder, where the variable names one.
fn folder() -> Option<PathBuf> {
    std::env::var_os(VAR)
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
}

/// What identifies the running executable's code: a rebuild changes it.
fn executable(h: &mut impl Hasher) {
    let exe = std::env::current_exe().ok();
    exe.hash(h);
    let meta = exe.and_then(|e| std::fs::metadata(e).ok());
    meta.as_ref().map(|m| m.len()).hash(h);
    let modified = meta.and_then(|m| m.modified().ok());
    modified.hash(h);
}

/// The file of one view's reference, 128 bits of key in its name.
fn file(
    dir: &Path,
    scene: &Scene,
    tris: &[([Vec3; 3], u32)],
    view_proj: Mat4,
    size: (u32, u32),
    sampling: AreaSampling,
) -> PathBuf {
    let mut key = Vec::new();
    for half in [0u8, 1] {
        let mut h = DefaultHasher::new();
        half.hash(&mut h);
        executable(&mut h);
        h.write(bytemuck::cast_slice(
            &tris
                .iter()
                .flat_map(|([a, b, c], o)| {
                    let o = f32::from_bits(*o);
                    [a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, o]
                })
                .collect::<Vec<f32>>(),
        ));
        for o in &scene.objects {
            o.casts_shadow.hash(&mut h);
        }
        // Lights, bounds and origin as their exact Debug text (Rust prints
        // floats so that they read back to the same bits).
        format!("{:?}", scene.lights).hash(&mut h);
        format!("{:?} {:?}", scene.bounds(), scene.origin()).hash(&mut h);
        h.write(bytemuck::bytes_of(&view_proj));
        size.hash(&mut h);
        sampling.side.hash(&mut h);
        key.push(h.finish());
    }
    dir.join(format!("{:016x}{:016x}.ref", key[0], key[1]))
}

/// A pixel's hit as it lies in the file (`present` 0 where nothing was hit).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FileHit {
    present: u32,
    object: u32,
    triangle: u32,
    t: f32,
    position: [f32; 3],
    normal: [f32; 3],
}

/// The file's first words: a tag (and its version), the size and the number of lights.
const TAG: u32 = 0x5245_4631;

/// A reference as bytes: the header, the time and rays, then per pixel its
/// hit, then per light its area flag and per pixel its visibility, N·L and
/// horizon flag, all native-endian (the file never leaves this machine).
fn to_bytes(r: &Reference) -> Vec<u8> {
    let mut b = Vec::new();
    let lights = r.visibility.len() as u32;
    b.extend_from_slice(bytemuck::cast_slice(&[TAG, r.width, r.height, lights]));
    b.extend_from_slice(bytemuck::bytes_of(&r.ms));
    b.extend_from_slice(bytemuck::bytes_of(&r.shadow_rays));
    let hits: Vec<FileHit> = (r.hits.iter())
        .map(|h| match h {
            None => bytemuck::Zeroable::zeroed(),
            Some(h) => FileHit {
                present: 1,
                object: h.object,
                triangle: h.triangle,
                t: h.t,
                position: h.position.to_array(),
                normal: h.normal.to_array(),
            },
        })
        .collect();
    b.extend_from_slice(bytemuck::cast_slice(&hits));
    for k in 0..lights as usize {
        b.extend_from_slice(bytemuck::bytes_of(&u32::from(r.area_light[k])));
        b.extend_from_slice(bytemuck::cast_slice(&r.visibility[k]));
        b.extend_from_slice(bytemuck::cast_slice(&r.lit_by[k]));
        let clipped: Vec<u32> = r.horizon_clipped[k].iter().map(|&c| u32::from(c)).collect();
        b.extend_from_slice(bytemuck::cast_slice(&clipped));
    }
    b
}

/// [`to_bytes`] read back; `None` for a file of another size or shape.
fn from_bytes(b: &[u8]) -> Option<Reference> {
    let mut at = 0;
    let mut take = |n: usize| -> Option<&[u8]> {
        let s = b.get(at..at + n)?;
        at += n;
        Some(s)
    };
    let head: Vec<u32> = bytemuck::pod_collect_to_vec(take(16)?);
    let (width, height, lights) = (head[1], head[2], head[3] as usize);
    if head[0] != TAG {
        return None;
    }
    let ms: f64 = bytemuck::pod_read_unaligned(take(8)?);
    let shadow_rays: u64 = bytemuck::pod_read_unaligned(take(8)?);
    let n = width as usize * height as usize;
    let hits: Vec<FileHit> = bytemuck::pod_collect_to_vec(take(n * size_of::<FileHit>())?);
    let hits = (hits.iter())
        .map(|h| {
            (h.present == 1).then(|| PixelHit {
                object: h.object,
                triangle: h.triangle,
                t: h.t,
                position: Vec3::from_array(h.position),
                normal: Vec3::from_array(h.normal),
            })
        })
        .collect();
    let mut r = Reference {
        width,
        height,
        hits,
        visibility: Vec::new(),
        lit_by: Vec::new(),
        area_light: Vec::new(),
        horizon_clipped: Vec::new(),
        ms,
        shadow_rays,
    };
    for _ in 0..lights {
        let area: u32 = bytemuck::pod_read_unaligned(take(4)?);
        r.area_light.push(area == 1);
        r.visibility
            .push(bytemuck::pod_collect_to_vec(take(n * 4)?));
        r.lit_by.push(bytemuck::pod_collect_to_vec(take(n * 4)?));
        let clipped: Vec<u32> = bytemuck::pod_collect_to_vec(take(n * 4)?);
        r.horizon_clipped
            .push(clipped.iter().map(|&c| c == 1).collect());
    }
    (at == b.len()).then_some(r)
}

/// [`try_render_reference`](super::try_render_reference) of a headless
/// run, read from the cache where it holds this view, and written to it
/// when it took long enough. Without `WORKBOOK_REFERENCE_CACHE`, only the
/// trace.
pub fn reference(
    scene: &Scene,
    view_proj: Mat4,
    width: u32,
    height: u32,
) -> anyhow::Result<Reference> {
    let sampling = AreaSampling::DEFAULT;
    let Some(dir) = folder() else {
        return try_render_reference_with(scene, view_proj, width, height, sampling);
    };
    let path = file(
        &dir,
        scene,
        &scene.world_triangles(),
        view_proj,
        (width, height),
        sampling,
    );
    let read = std::fs::read(&path).ok().and_then(|b| from_bytes(&b));
    if let Some(r) = read.filter(|r| (r.width, r.height) == (width, height)) {
        return Ok(r);
    }
    let r = try_render_reference_with(scene, view_proj, width, height, sampling)?;
    store(&path, &r);
    Ok(r)
}

/// Writes a reference that was worth caching (atomically: a file written
/// beside it, then renamed, so that a reader never sees half of one). A
/// cache that cannot be written is only a slower run: the error is dropped.
fn store(path: &Path, reference: &Reference) {
    if reference.ms < WORTH_MS {
        return;
    }
    let Some(dir) = path.parent() else {
        return;
    };
    let _ = std::fs::create_dir_all(dir);
    let tmp = path.with_extension(format!("{}.part", std::process::id()));
    if std::fs::write(&tmp, to_bytes(reference)).is_ok() {
        let _ = std::fs::rename(&tmp, path);
    } else {
        let _ = std::fs::remove_file(&tmp);
    }
}

#[cfg(test)]
#[path = "unit_tests/cache.rs"]
mod tests;
