//! Generators for meshes, sphere lights and edges (silhouette and wedge kernels).
