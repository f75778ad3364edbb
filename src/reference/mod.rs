//! The two [ground truths](crate::definitions#exact-and-monte-carlo-references): [`exact`] visibility by the
//! receiver view, and [`monte_carlo`] light sampling with occlusion rays.
//! Every error the project reports is measured against [`exact`], and
//! [`exact`] is checked against [`monte_carlo`].
//!
//! Both read the scene's triangles through
//! [`Occluders`](crate::bvh::Occluders): one flat list over all meshes,
//! each triangle tagged with its object id (mesh index), held by a
//! [`Bvh`](crate::bvh::Bvh) built once per scene.
//!
//! ```
//! use softshadow::glam::DVec3;
//! use softshadow::bvh::{Bvh, Occluders};
//! use softshadow::reference::{exact, monte_carlo};
//! use softshadow::reference::stats::{agreement_tolerance, student_t_two_sided_quantile};
//! use softshadow::scene::{Light, Mesh, Scene};
//!
//! // A sphere light of radius 1/2 at height 4; a large card at height 1
//! // whose edge, seen from the receiver at the origin, crosses the light's
//! // centre: half the light is hidden.
//! let light = Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5)?;
//! let card = Mesh::new(
//!     vec![DVec3::new(0.0, -9.0, 1.0), DVec3::new(9.0, 0.0, 1.0), DVec3::new(0.0, 9.0, 1.0)],
//!     vec![[0, 1, 2]],
//! )?;
//! let scene = Scene::new(light).with_mesh("card", card);
//! let bvh = Bvh::new(Occluders::from_scene(&scene));
//!
//! let v = exact::visibility(&bvh, &light, DVec3::ZERO)?;
//! assert!((v - 0.5).abs() < 1e-12);
//!
//! let options = monte_carlo::Options::new(4096);
//! let mc = monte_carlo::visibility(&bvh, &light, DVec3::ZERO, &options)?;
//! // Within the estimate's standard error, at a 1e-6 false-failure rate.
//! let q = student_t_two_sided_quantile(1e-6, monte_carlo::REPLICATES - 1);
//! assert!((mc.visibility - v).abs() <= agreement_tolerance(&mc, 4096, q));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod exact;
pub mod monte_carlo;
pub mod stats;

pub use stats::{agree, Agreement};
