//! Finite-difference Jacobians (the default when a problem has no analytic ones).
