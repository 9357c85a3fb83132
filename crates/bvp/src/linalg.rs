//! Small dense linear algebra without allocation (LU with partial pivoting).
