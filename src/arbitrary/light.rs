//! Generators for the falloff, SSOC distortion and linear-light kernels.
