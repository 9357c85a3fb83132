//! Problems with known answers, shared by tests, benches and examples.
