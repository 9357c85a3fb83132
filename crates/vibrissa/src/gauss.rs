//! Quadrature of the surface profiles and the rod's energy: 10-point Gauss–Legendre on a panel.

const GL_X: [f64; 10] = [
    -0.973_906_528_517_171_7,
    -0.865_063_366_688_984_5,
    -0.679_409_568_299_024_4,
    -0.433_395_394_129_247_2,
    -0.148_874_338_981_631_2,
    0.148_874_338_981_631_2,
    0.433_395_394_129_247_2,
    0.679_409_568_299_024_4,
    0.865_063_366_688_984_5,
    0.973_906_528_517_171_7,
];
const GL_W: [f64; 10] = [
    0.066_671_344_308_688_14,
    0.149_451_349_150_580_6,
    0.219_086_362_515_982_04,
    0.269_266_719_309_996_35,
    0.295_524_224_714_752_87,
    0.295_524_224_714_752_87,
    0.269_266_719_309_996_35,
    0.219_086_362_515_982_04,
    0.149_451_349_150_580_6,
    0.066_671_344_308_688_14,
];

/// 10-point Gauss–Legendre of `f` on `[a, b]`.
pub(crate) fn gauss10(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (c, r) = (0.5 * (a + b), 0.5 * (b - a));
    r * GL_X
        .iter()
        .zip(&GL_W)
        .map(|(x, w)| w * f(c + r * x))
        .sum::<f64>()
}

/// [`gauss10`] with the ten values of `f` asked for at once (the same nodes and the same sum,
/// so the same bits).
pub(crate) fn gauss10_batch(a: f64, b: f64, f: impl FnOnce([f64; 10]) -> [f64; 10]) -> f64 {
    let (c, r) = (0.5 * (a + b), 0.5 * (b - a));
    let v = f(GL_X.map(|x| c + r * x));
    r * GL_W.iter().zip(v).map(|(w, f)| w * f).sum::<f64>()
}

/// The nodes and weights of [`gauss10`] on `[a, b]` (for sums over the same nodes with several
/// integrands).
pub(crate) fn nodes10(a: f64, b: f64) -> [(f64, f64); 10] {
    let (c, r) = (0.5 * (a + b), 0.5 * (b - a));
    std::array::from_fn(|i| (c + r * GL_X[i], r * GL_W[i]))
}
