//! Frame-time controllers.
