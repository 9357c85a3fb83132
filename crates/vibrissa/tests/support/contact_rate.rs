//! How fast a row's contacts approach their friction limits (tests/contact.rs, contact_forces.rs):
//! the allowance of a located slip.

use vibrissa::drag::ContactState;

/// The mean rate at which the contacts' friction condition `g` (`|T| − μ N`, or a stretch's
/// own) changes from the state `a` to the state `b` a parameter `length` apart (contact by
/// contact where the set kept its contacts, else bounded by the largest values).
pub fn rate(
    a: &[ContactState],
    b: &[ContactState],
    g: &dyn Fn(&ContactState) -> f64,
    length: f64,
) -> f64 {
    if length == 0.0 {
        return 0.0;
    }
    let change = if a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.tip == y.tip) {
        a.iter()
            .zip(b)
            .map(|(x, y)| (g(x) - g(y)).abs())
            .fold(0.0, f64::max)
    } else {
        let most = |v: &[ContactState]| v.iter().map(|k| g(k).abs()).fold(0.0, f64::max);
        most(a) + most(b)
    };
    change / length.abs()
}
