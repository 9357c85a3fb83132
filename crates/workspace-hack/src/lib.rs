//! Empty on purpose: see `Cargo.toml` (feature unification across the workspace's members).
