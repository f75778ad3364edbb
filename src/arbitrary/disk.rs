//! Generators for the disk-occlusion kernels.
