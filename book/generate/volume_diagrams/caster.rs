//! The caster chapter 05's pictures show: lesson 05's cube from its scene,
//! with its adjacency, lit by the scene's point light, and the camera
//! that views it.

use anyhow::{Context, Result};
use common::glam::dcamera::rh::view::look_at_mat4;
use common::glam::{DMat4, DVec3, Vec3};
use common::scene::camera::perspective;
use common::scene::{Far, LightKind, Scene};
use workbook::lesson_05::adjacency::Adjacency;
use workbook::lesson_05::silhouette::{face_facing, LightDir};

use super::draw::pixel;
use crate::diagrams::svg::P;

/// Lesson 05's cube caster in world space, lit by the scene's point light.
pub(super) struct Caster {
    pub(super) adj: Adjacency,
    pub(super) light: DVec3,
    pub(super) facing: Vec<bool>,
    pub(super) centre: DVec3,
    /// A fixed camera that sees the lit faces and the volume behind them.
    pub(super) view: DMat4,
    pub(super) proj: DMat4,
}

impl Caster {
    pub(super) fn from_scene(scene: &Scene) -> Result<Caster> {
        let cube = scene.objects.iter().find(|o| o.mesh_name == "cube");
        let cube = cube.context("lesson_05.toml: no cube caster")?;
        let light = scene.lights.iter().find_map(|l| match l.kind {
            LightKind::Point { position, .. } => Some(position),
            _ => None,
        });
        let light = light.context("lesson_05.toml: no point light")?;
        let world: Vec<Vec3> = cube
            .mesh
            .positions
            .iter()
            .map(|p| cube.model.transform_point3(p.as_dvec3()).as_vec3())
            .collect();
        let adj = Adjacency::from_triangles(&world, &cube.mesh.indices);
        let facing = face_facing(&adj, LightDir::Point(light.as_vec3()));
        let centre = cube.model.transform_point3(DVec3::ZERO);
        let eye = centre + DVec3::new(-1.4, 2.4, 4.6);
        let view = look_at_mat4(eye, centre + DVec3::new(-0.6, -0.4, 0.0), DVec3::Y);
        let proj = perspective(40.0, 1.0, 0.1, Far::Finite(100.0));
        Ok(Caster {
            adj,
            light,
            facing,
            centre,
            view,
            proj,
        })
    }
    pub(super) fn pos(&self, i: u32) -> DVec3 {
        self.adj.positions[i as usize].as_dvec3()
    }
    pub(super) fn screen(&self, p: DVec3) -> P {
        pixel(self.proj * self.view, 2.0, 2.0, p.extend(1.0)).unwrap_or((0.0, 0.0))
    }
    pub(super) fn depth(&self, pts: &[DVec3]) -> f64 {
        pts.iter()
            .map(|p| self.view.transform_point3(*p).z)
            .sum::<f64>()
            / pts.len() as f64
    }
}
