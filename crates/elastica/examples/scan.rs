//! Print the closed-form stiction scan: `cargo run -p elastica --example scan -- 0.75`
fn main() -> Result<(), elastica::ElasticaError> {
    let eta: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.75);
    let scan = elastica::ClosedFormScan::new(eta)?;
    println!("{:?}", scan.phase0_end);
    println!("turning {:?}", scan.turning);
    println!("fold {:?}", scan.fold);
    println!("mu_max {:?}", scan.mu_max()?);
    println!("d,mu,alpha,phi1,f,m_base,flex");
    for p in scan.points(11, 10)? {
        println!(
            "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{}",
            p.d, p.mu, p.alpha, p.phi1, p.f, p.m_base, p.flex
        );
    }
    Ok(())
}
