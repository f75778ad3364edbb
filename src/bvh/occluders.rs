//! [`Occluders`]: every occluding triangle of a scene in one flat list.

use crate::scene::{Mesh, Scene};
use glam::DVec3;

/// Every occluding triangle of a scene, flattened: corners in `f64`, and the
/// object id (mesh index) of each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Occluders {
    triangles: Vec<[DVec3; 3]>,
    objects: Vec<u32>,
}

impl Occluders {
    /// The triangles of `meshes`, in mesh order then triangle order.
    #[must_use]
    pub fn from_meshes(meshes: &[Mesh]) -> Occluders {
        let mut out = Occluders::default();
        for (object, mesh) in meshes.iter().enumerate() {
            for t in mesh.triangles() {
                out.triangles.push(t.map(|i| mesh.positions()[i as usize]));
                out.objects.push(object as u32);
            }
        }
        out
    }

    /// The triangles of a scene.
    #[must_use]
    pub fn from_scene(scene: &Scene) -> Occluders {
        Occluders::from_meshes(scene.meshes())
    }

    /// Triangles given directly (object id 0 for all). Corners need not be
    /// finite here; non-finite triangles are ignored by both references.
    #[must_use]
    pub fn from_triangles(triangles: Vec<[DVec3; 3]>) -> Occluders {
        let objects = vec![0; triangles.len()];
        Occluders { triangles, objects }
    }

    /// The triangles.
    #[must_use]
    pub fn triangles(&self) -> &[[DVec3; 3]] {
        &self.triangles
    }

    /// The object id of each triangle.
    #[must_use]
    pub fn objects(&self) -> &[u32] {
        &self.objects
    }

    /// The number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there is no triangle.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}
