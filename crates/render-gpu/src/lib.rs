//! GPU renderer.
