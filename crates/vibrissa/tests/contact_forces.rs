//! Issue 31, "Drag across any texture": the per-contact property. Over random scenes
//! (corrugations, heights, friction pairs, uniform and tapered rods, point and round tips), every
//! contact of every row of a drag and of every slip lies on the surface, pushes (no tensile
//! contact), and holds by Coulomb's law: stuck `|T| ≤ μs N`, sliding `|T| = μk N`; every slip
//! dissipates the energy it releases.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use vibrissa::drag::{ContactState, DragEvent, DragRow, Hold};

#[path = "support/contact_rate.rs"]
mod contact_rate;
#[path = "support/cpu_guard.rs"]
mod cpu_guard;
use contact_rate::rate;
use vibrissa::surface::{Height, SurfaceProfile};
use vibrissa::{
    drag, Cancel, DragOptions, DragResult, Event, Scene, SolverConfig, Stiffness, StopReason,
    VibrissaError,
};

/// A random scene and its friction pair.
#[derive(Clone, Debug)]
struct Case {
    amp: f64,
    wave: f64,
    phase: f64,
    eta: f64,
    mu_s: f64,
    ratio: f64,
    taper: Option<f64>,
    radius: f64,
    d_max: f64,
}

/// How far a contact point may lie off the surface. The contact condition is a row of the
/// Newton residual (`y − h(x)`, a round tip's centre `y + r cos θ − h(x_c)`), iterated to the
/// corrector's tolerance `min(tol/10, 1e-9)` in the step (1e-11 at the default tol 1e-10) and
/// converging quadratically past it; the side's point is the rod integrated to its `s` (the same
/// integrator at tol 1e-10). Met: at most 6.4e-13 over the survey's 76 drags.
const ON_SURFACE: f64 = 1e-12;

/// Slack of the friction inequalities and equalities, relative to `N` (and of `N ≥ 0` absolute
/// on forces of order 1): the thresholds are located in `λ` to 1e-13 on the side where the state
/// still holds, and a slider's `T − ratio·N = 0` is a residual row like the contact's.
const FRICTION: f64 = 1e-10;

/// A contact's slip limit (`|T| = μs N`, in the foot's `d`) and a slip's end (`dir·T = μk N`, in
/// the slide's arc length `λ`) are located to `1e-13·(1 + λ)` by Brent's method
/// (`events::locate`), on the side where the old state still holds, and `inside` may back the
/// point off by a few such steps: allowed `4e-13·(1 + λ)` times the mean rate at which the
/// contacts' `|T| − μ N` changes over the stick or the slip (where a trapped pair of contacts
/// relaxes from μs to μk over a slide of 1e-8 that rate is ~3e7, and the located ratio lies
/// ~1e-8 off μk, not 1e-10). A slip's end is located in its last contact state: where the set
/// changed inside the slip, the rate over that state counts where it is the larger (seed 44: a
/// round tip touches down beside a sliding side 2.4e-7 of slide before the end, and the side's
/// `|T| − μk N` falls by 2.8 over it, a rate of 1.2e7 against the slip's mean 2.4e3).
const LOCATE: f64 = 4e-13;

/// Seconds of its thread's CPU after which a drag counts as hung (a case takes well under a
/// second in the test profile; this only keeps a drag that does not end from blocking the test).
const HANG: u64 = 30;

/// [`HANG`] for the drags of thousands of slips (most `#[ignore = "slow: …"]`: about 30 s of
/// CPU in release, several minutes in the test profile).
const SLOW_HANG: u64 = 1800;

/// The energy balance of a slip (the released elastic energy equals the work of the sliding
/// contacts) and of a stick (the foot's work equals the energy's change plus the passive
/// sliders' work): the metered integrals agree with the whole to 1e-11 per step (docs/model.md).
const ENERGY: f64 = 1e-8;

fn cases() -> impl Strategy<Value = Case> {
    (
        (0.001..0.02f64, 0.05..0.5f64, 0.0..std::f64::consts::TAU),
        (0.4..0.9f64, 0.3..0.8f64, 0.2..0.9f64),
        prop_oneof![Just(None), (0.3..1.0f64).prop_map(Some)],
        prop_oneof![Just(0.0), 0.002..0.01f64],
        0.03..0.1f64,
    )
        .prop_map(
            |((amp, wave, phase), (eta, mu_s, ratio), taper, radius, d_max)| Case {
                // (below the point tip's documented 45° slope limit, 2πA/W < 1: steeper
                // corrugations are refused, docs/model.md)
                amp: amp.min(0.9 * wave / std::f64::consts::TAU),
                wave,
                phase,
                eta,
                mu_s,
                ratio,
                taper,
                radius,
                d_max,
            },
        )
}

fn scene(c: &Case) -> Scene {
    Scene {
        eta: c.eta,
        surface: SurfaceProfile::Sine {
            amplitude: c.amp,
            wavelength: c.wave,
            phase: c.phase,
        },
        stiffness: match c.taper {
            Some(ratio) => Stiffness::Taper { ratio },
            None => Stiffness::default(),
        },
        tip_radius: c.radius,
        ..Scene::default()
    }
}

/// Whether a drag stopped for a named physical reason (its rows up to there are checked).
fn physical(stop: &StopReason) -> bool {
    matches!(
        stop,
        StopReason::DMax
            | StopReason::LiftOff { .. }
            | StopReason::FoldInD { .. }
            | StopReason::ContactChange { .. }
            | StopReason::Jam { .. }
    )
}

/// Whether the start failed at a named physical stop of its march (the press or the growth of
/// the surface's shape: a contact state the model cannot continue in, a jam, a lift-off).
fn physical_start(reason: &str) -> bool {
    ["contact change at", "jam at", "lift-off at"]
        .iter()
        .any(|k| reason.contains(k))
}

std::thread_local! {
    /// The worst values a drag's check met, for the survey: `|gap|`, `−min N`, the stuck
    /// contacts' `(|T| − μs N)/max(N, 1)`, the sliding ones' `|dir·T − μk N|/max(N, 1)`, a
    /// slip's `|dissipated − released|`.
    static WORST: std::cell::Cell<[f64; 5]> = const { std::cell::Cell::new([f64::NEG_INFINITY; 5]) };
}

/// Takes `v` into the worst value `i`.
fn see(i: usize, v: f64) {
    WORST.with(|w| {
        let mut a = w.get();
        a[i] = a[i].max(v);
        w.set(a);
    });
}

/// The friction force the contact `k` needs: `T` of a point contact, a lying stretch's friction
/// ratio times its `N` (its `T` is its resultant's, part of which the surface's curvature takes
/// up without friction: a stretch holds at `T/N` 0.30001 under μs 0.3, seed 11).
fn friction(k: &ContactState) -> f64 {
    k.friction_ratio.map_or(k.tangential, |r| r * k.normal)
}

/// The contact `c` (of `what`) against the surface `h` and Coulomb's law with `(μs, μk)` (for a
/// lying stretch, by the friction ratio it needs: [`friction`]), the friction conditions to
/// `FRICTION·N` and `at` (a located point's allowance, 0 elsewhere).
fn check_contact(
    h: &Height,
    (mu_s, mu_k): (f64, f64),
    (c, at): (&ContactState, f64),
    what: &str,
) -> Result<(), TestCaseError> {
    let gap = c.y - h.h(c.x);
    see(0, gap.abs());
    see(1, -c.normal);
    prop_assert!(
        gap.abs() <= ON_SURFACE,
        "{what}: {c} lies {gap:.3e} off the surface"
    );
    prop_assert!(c.normal >= 0.0, "{what}: {c} is tensile");
    let slack = FRICTION * c.normal.max(1.0) + at;
    let t = friction(c);
    prop_assert!(t.is_finite(), "{what}: {c} needs no finite friction");
    match c.hold {
        Hold::Stuck => {
            see(2, (t.abs() - mu_s * c.normal) / c.normal.max(1.0));
            prop_assert_eq!(c.mu, mu_s, "{}: {}", what, c);
            prop_assert!(
                t.abs() <= mu_s * c.normal + slack,
                "{what}: stuck {c} beyond mu_s N by {:.3e}",
                t.abs() - mu_s * c.normal
            );
        }
        Hold::Sliding { dir } => {
            see(3, (dir * t - mu_k * c.normal).abs() / c.normal.max(1.0));
            prop_assert_eq!(c.mu, mu_k, "{}: {}", what, c);
            prop_assert!(
                (dir * t - mu_k * c.normal).abs() <= slack,
                "{what}: sliding {c} off dir mu_k N by {:.3e}",
                dir * t - mu_k * c.normal
            );
        }
        Hold::Slipping { dir } => {
            // (the slip goes on while the contact needs more than kinetic friction gives)
            prop_assert_eq!(c.mu, mu_k, "{}: {}", what, c);
            prop_assert!(
                dir * t >= mu_k * c.normal - slack,
                "{what}: slipping {c} below dir mu_k N by {:.3e}",
                mu_k * c.normal - dir * t
            );
        }
        Hold::Free => prop_assert!(false, "{what}: frictionless {c} in a drag"),
    }
    Ok(())
}

/// The allowances of the located points of each slip (`LOCATE`): its slip limit, in `d` over
/// the stick before it, and its end, in the slide's arc length over the slip (`last`: the
/// slips' [`last_pieces`]).
fn allowances(r: &DragResult, mu: (f64, f64), last: &[Option<&DragRow>]) -> Vec<(f64, f64)> {
    (r.slips.iter().enumerate())
        .map(|(i, e)| {
            let k = &r.slip_contacts[i];
            let start = match i {
                0 => &r.rows[0].contacts,
                _ => &r.slip_contacts[i - 1].after,
            };
            let g = |m: f64| move |k: &ContactState| friction(k).abs() - m * k.normal;
            let stick = rate(start, &k.before, &g(mu.0), e.d - e.d_stick);
            let mut slide = rate(&k.before, &k.after, &g(mu.1), e.jump);
            // (the end is located in the slip's last contact state: where the set changed in
            // the slip, the rate there, not the slip's mean)
            if let Some(Some(row)) = last.get(i) {
                let moved = slid(&row.contacts, &k.after);
                if moved > 0.0 {
                    slide = slide.max(rate(&row.contacts, &k.after, &g(mu.1), moved));
                }
            }
            (
                LOCATE * (1.0 + e.d.abs()) * stick,
                LOCATE * (1.0 + e.jump.abs()) * slide,
            )
        })
        .collect()
}

/// Per slip, the row of the last change of the contact set inside it (the last event between
/// its `slip` and its `slip_end` rows), `None` where the set did not change; empty where the
/// rows do not hold one `slip` row per slip.
fn last_pieces(r: &DragResult) -> Vec<Option<&DragRow>> {
    let mut out = Vec::new();
    let mut inside = false;
    for row in &r.rows {
        match row.event {
            Some(DragEvent::Slip) => {
                out.push(None);
                inside = true;
            }
            Some(DragEvent::SlipEnd) => inside = false,
            Some(DragEvent::Contact(_)) if inside => {
                if let Some(last) = out.last_mut() {
                    *last = Some(row);
                }
            }
            _ => {}
        }
    }
    if out.len() != r.slips.len() {
        out.clear();
    }
    out
}

/// How far the contact that slips at `row` (its first contact [`Hold::Slipping`]; 0 where none)
/// moved to the slip's end `after`: the distance to the nearest contact of `after` of its kind
/// (tip or side), the chord of the surface's arc over so short a piece.
fn slid(row: &[ContactState], after: &[ContactState]) -> f64 {
    let Some(k) = row.iter().find(|k| matches!(k.hold, Hold::Slipping { .. })) else {
        return 0.0;
    };
    (after.iter().filter(|a| a.tip == k.tip))
        .map(|a| (a.x - k.x).hypot(a.y - k.y))
        .fold(f64::INFINITY, f64::min)
        .min(f64::MAX)
}

/// Every row's and every slip's contacts, and every slip's energy balance.
fn check(c: &Case, r: &DragResult, h: &Height) -> Result<(), TestCaseError> {
    let mu = (c.mu_s, c.ratio * c.mu_s);
    let last = last_pieces(r);
    let allow = allowances(r, mu, &last);
    // (an event row is a located point: the largest allowance of the drag)
    let event = allow.iter().map(|a| a.0.max(a.1)).fold(0.0, f64::max);
    for row in &r.rows {
        let what = format!("row at d = {} ({:?}, {:?})", row.d, row.phase, row.event);
        prop_assert!(!row.contacts.is_empty(), "{what}: no contact");
        // the row's totals are its contacts' sums
        let n: f64 = row.contacts.iter().map(|k| k.normal).sum();
        prop_assert!(
            (n - row.normal).abs() <= 1e-12 * (1.0 + n.abs()),
            "{what}: N {n}"
        );
        if c.radius > 0.0 {
            let tip = row.contacts.last().filter(|k| k.tip);
            prop_assert_eq!(tip.map(|k| k.x), row.x_contact, "{}", what);
        }
        let at = if row.event.is_some() { event } else { 0.0 };
        for k in &row.contacts {
            check_contact(h, mu, (k, at), &what)?;
        }
    }
    prop_assert_eq!(r.slip_contacts.len(), r.slips.len());
    for ((i, e), &(stick, slide)) in r.slips.iter().enumerate().zip(&allow) {
        let what = format!("slip {i} at d = {}", e.d);
        let contacts = &r.slip_contacts[i];
        for k in &contacts.before {
            check_contact(h, mu, (k, stick), &format!("{what}, before"))?;
        }
        // (a driver that lets go ends its slip with the others held, docs/model.md)
        let let_go = matches!(
            last.get(i),
            Some(Some(row)) if row.event == Some(DragEvent::Contact(Event::Release))
                && row.contacts.len() > contacts.after.len()
        );
        prop_assert!(
            let_go
                || contacts
                    .after
                    .iter()
                    .any(|k| matches!(k.hold, Hold::Sliding { .. })),
            "{what}: no contact slid"
        );
        for k in &contacts.after {
            check_contact(h, mu, (k, slide), &format!("{what}, after"))?;
        }
        let (stick, slip) = e.imbalance().unwrap();
        see(4, slip.abs());
        prop_assert!(
            slip.abs() <= ENERGY,
            "{what}: slip imbalance {slip} ({e:?})"
        );
        prop_assert!(
            stick.abs() <= ENERGY,
            "{what}: stick imbalance {stick} ({e:?})"
        );
    }
    Ok(())
}

/// The drag of the case `c` checked; what it did, in words.
fn run(c: &Case) -> Result<String, TestCaseError> {
    run_in(c, scene(c))
}

/// As [`run`], on the scene `s` (the case's surface, heights and friction on another rod).
fn run_in(c: &Case, s: Scene) -> Result<String, TestCaseError> {
    run_points(c, s, 11)
}

/// As [`run_in`], with `points` output points (the program's default is 201: its march steps
/// end on them).
fn run_points(c: &Case, s: Scene, points: usize) -> Result<String, TestCaseError> {
    run_bounded(c, s, points, HANG)
}

/// As [`run_points`], a hang being a drag that takes longer than `hang` seconds.
fn run_bounded(c: &Case, s: Scene, points: usize, hang: u64) -> Result<String, TestCaseError> {
    run_checked(c, s, points, hang).map(|(out, _)| out)
}

/// As [`run_bounded`], with the drag's result (`None` where it had no start).
fn run_checked(
    c: &Case,
    s: Scene,
    points: usize,
    hang: u64,
) -> Result<(String, Option<DragResult>), TestCaseError> {
    WORST.with(|w| w.set([f64::NEG_INFINITY; 5]));
    // (a refused scene is no drag: a round tip wider than a groove is round)
    prop_assume!(s.validate().is_ok());
    let (rod, surface) = s.parts().unwrap();
    let h = surface.profile().unwrap();
    let flag = Arc::new(AtomicBool::new(false));
    let o = DragOptions {
        d_max: c.d_max,
        points,
        mu_s: Some(c.mu_s),
        mu_k: Some(c.ratio * c.mu_s),
        energy_balance: true,
        solver: SolverConfig {
            cancel: Cancel::new(flag.clone()),
            ..SolverConfig::default()
        },
        ..DragOptions::default()
    };
    // (a drag that does not end, a hang, is cancelled after `hang` seconds of its thread's CPU
    // and fails: its stop is `cancelled`, no physical one)
    let r = cpu_guard::guarded(flag, hang, || drag(&rod, &surface, &o));
    let r = match r {
        Ok(r) => r,
        // (a start the model cannot continue in is named as a drag's stop is: accepted)
        Err(VibrissaError::NoStart { reason }) if physical_start(&reason) => {
            return Ok((format!("no start: {reason}"), None));
        }
        // (a pressed rod that snaps or lies down as the texture grows: named, with its place)
        Err(e @ (VibrissaError::StartSnaps { .. } | VibrissaError::StartLies { .. })) => {
            return Ok((format!("no start: {e}"), None));
        }
        Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
    };
    prop_assert!(physical(&r.stop), "stopped: {}", r.stop);
    check(c, &r, h)?;
    let most = r.rows.iter().map(|w| w.contacts.len()).max().unwrap_or(0);
    let w = WORST.with(|w| w.get());
    let out = format!(
        "{} rows, {} slips, up to {most} contacts; worst |gap| {:.1e}, -N {:.1e}, stuck \
         (|T| - mu_s N)/max(N, 1) {:.1e}, sliding |T - mu_k N|/max(N, 1) {:.1e}, slip energy \
         {:.1e}; stopped: {}",
        r.rows.len(),
        r.slips.len(),
        w[0],
        w[1],
        w[2],
        w[3],
        w[4],
        r.stop
    );
    Ok((out, Some(r)))
}

/// The property's seed in the default test run: seed 1's 16 scenes take about 2 s in the test
/// profile (1.6 s of CPU in release). Seeds 2 and 4 pass too, in 29 and 27 s of CPU in release;
/// seed 3 holds drags of thousands of slips that run past [`HANG`] seconds and are cancelled as
/// hung (one of them, shrunk by proptest, reaches d_max in 15 490 slips and 33 s of CPU when run
/// alone in release). Run other seeds in release with `PROPTEST_RNG_SEED`, and a survey of 100
/// scenes with `survey`.
const SEED: u64 = 1;

/// `PROPTEST_CASES` cases (else 16) from `PROPTEST_RNG_SEED` (else `SEED`); failures are not
/// persisted (those found are tests of their own, below).
fn config() -> ProptestConfig {
    let mut c = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 16;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(SEED);
    }
    c.failure_persistence = None;
    c
}

proptest! {
    #![proptest_config(config())]
    #[test]
    fn every_contact_holds_by_coulomb_on_the_surface(c in cases()) {
        run(&c)?;
    }
}

/// A scene where the property failed (issue 31's drag failures, found by `survey` and the
/// property's seeds), checked by [`run`].
fn open(c: &Case) {
    if let Err(e) = run(c) {
        panic!("{c:?}: {e}");
    }
}

/// Was open: the start's growth of the surface shape ended in a solver failure (Newton at a fold
/// of the amplitude march). The side at s = 0.802788 begins to lie along the surface just before
/// (its relative curvature reaches zero at amplitude fraction 0.218069, the fold was at 0.219303):
/// the start stops there by name.
#[test]
fn a_start_whose_side_begins_to_lie_is_named() {
    open(&Case {
        amp: 0.0016877583175643218,
        wave: 0.18096389863709944,
        phase: 4.951361800857984,
        eta: 0.5242558142024888,
        mu_s: 0.7519295059193076,
        ratio: 0.5563486764765111,
        taper: Some(0.4070828895393095),
        radius: 0.006724571848806922,
        d_max: 0.04613312283829712,
    });
}

/// Was open: the fold row of a slip that snaps had the tip tensile, N = -2.0e-4 (the tip touches
/// down in the slide into a state that pulls at it); now the drag stops there by name, without
/// the row (march.rs `pulling`).
#[test]
fn no_tensile_tip_at_a_slips_fold() {
    open(&Case {
        amp: 0.0176903055763737,
        wave: 0.13923824524545325,
        phase: 0.0,
        eta: 0.4909001835488721,
        mu_s: 0.3,
        ratio: 0.2,
        taper: None,
        radius: 0.0,
        d_max: 0.03,
    });
}

/// Was "trapped slide, not followed" (issue 31's texture grid, 0.02/0.5/0, taper 0.3, r = 0.005,
/// the paper's drag settings): the tip slipped beside a side that holds in slips shorter than
/// the tolerance, and the drag stopped at d = 0.006137. Its creep is followed now as a slide
/// with μk in the stick (drag.rs `creeps`), and the drag reaches d_max with every contact by
/// Coulomb and every slip's and stick's energy balance.
#[test]
fn a_tip_creeping_beside_a_side_that_holds_slides_on() {
    let c = grid_case(0.02, 0.5, 0.0, 0.005);
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was open: a round tip and a side slipped in turn at d = 0.00623 without end (each held while
/// the other slid, each building up to μs again; cancelled after HANG s). A contact that breaks
/// free during a slip now slides along at its limit and relaxes to μk in turn (drag.rs
/// `slide_driver`), and the drag ends by name with every contact by Coulomb and every slip's
/// energy balance.
#[test]
fn a_round_tip_and_a_side_that_break_free_in_one_slip_slide_together() {
    open(&Case {
        amp: 0.010414057520175402,
        wave: 0.07270383688765461,
        phase: 3.9946570862470656,
        eta: 0.5457671866630984,
        mu_s: 0.7000372535645574,
        ratio: 0.6625989586125405,
        taper: None,
        radius: 0.008719641657830122,
        d_max: 0.04337003064043231,
    });
}

/// Was a drag that did not pass d = 2e-11 (cancelled after HANG s): its slips' slides went
/// through the fold passage, which followed each to its target far past the slip's end. With the
/// passage ending where an event of the march has ended it ran to a snap at d = 0.010773 (3325
/// slips), where a passive slider's halt was located at a root of the solver's noise just before
/// its lift-off; with that halt taken for the lift-off (march.rs `shadows`) it reaches d_max
/// (3455 slips), every contact by Coulomb and every slip's energy to 1e-8.
#[test]
fn a_drag_that_hung_at_its_start_runs_to_d_max() {
    let c = Case {
        amp: 0.013862691721217343,
        wave: 0.09726705331030241,
        phase: 5.118179006378352,
        eta: 0.6258910939137124,
        mu_s: 0.5359607936396033,
        ratio: 0.6256118404486513,
        taper: Some(0.4010038067345833),
        radius: 0.002672239678129047,
        d_max: 0.03240596615760605,
    };
    // (3455 slips: about 18 s in the test profile alone, so the 30 s of `HANG` is too close
    // on a loaded 2-core machine; the bound only catches a drag that does not end)
    let out = run_bounded(&c, scene(&c), 11, SLOW_HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was open: a sliding side peels back to the tip during the slip: the work metered, 0.00662,
/// was not the energy released, 0.01147 (slip 4, d = 0.043355). The slip's family moves its
/// driver's place by `dir·λ`, and the tip that the driver became held its place at the event's
/// `λ` as its anchor: the rod jumped on by a second `λ` there, releasing energy no friction took
/// (events.rs `driver_anchor`; a tip that lies down as the driver is the same). The energy of
/// every slip balances to 1e-8 now.
#[test]
fn energy_balances_at_a_slip_whose_side_peels_back() {
    open(&Case {
        amp: 0.00477953391473403,
        wave: 0.22828372884181566,
        phase: 3.7147902338111254,
        eta: 0.5490510133066397,
        mu_s: 0.6352657620313871,
        ratio: 0.8176756744529555,
        taper: None,
        radius: 0.0,
        d_max: 0.061043731868745836,
    });
}

/// A survey scene whose slip did not balance for the same reason (before `driver_anchor`:
/// slip 60 at d = 0.020385 metered 2.669e-7 of 4.456e-7 released on a tapered rod): every
/// contact by Coulomb and every slip's energy to 1e-8.
#[test]
fn energy_balances_at_the_surveys_slip_whose_driver_changes_kind() {
    open(&Case {
        amp: 0.006358914161537145,
        wave: 0.3414654663551734,
        phase: 5.470478932591279,
        eta: 0.6417841746787663,
        mu_s: 0.3863941856273612,
        ratio: 0.583027647928206,
        taper: Some(0.36222078619172193),
        radius: 0.0,
        d_max: 0.0818268486332887,
    });
}

/// Was open: a survey scene whose slip 14 (d = 0.076044) metered 0.0032121 of 0.0042096
/// released before `driver_anchor`; with events that end and come back inside a slip's step
/// located (march.rs `dipped`) the drag then failed in the slip at d = 0.08316 (Newton's residual
/// NaN on the slide's first step). There the driving side peeled back to the tip at
/// λ = 1.50145105e-3, and `dipped` took the free tip's height at that point, 6.7e-16 with the
/// side 1.5e-13 before the tip, for a touchdown 1.4e-13 earlier: in the state side+tip so made
/// the side's place along the rod moves by 2.75 per unit λ, and the first step's prediction put
/// it past the tip. The end of a free tail that short is rounding on a curved surface as on a
/// line (watch.rs `TAIL`), and a touchdown located within the smallest step of a peel-back is
/// that peel-back (march.rs `shadows`; each mends this scene alone): the side peels back, and the
/// drag reaches d_max (18 slips), every contact by Coulomb and every slip's energy to 1e-8.
#[test]
fn a_side_peeling_back_to_the_tip_is_no_touchdown_of_its_tail() {
    let c = Case {
        amp: 0.01972282810031794,
        wave: 0.38083573637334206,
        phase: 6.1994446304066715,
        eta: 0.6409945782739707,
        mu_s: 0.5165164426954519,
        ratio: 0.6414462897446284,
        taper: None,
        radius: 0.0,
        d_max: 0.08715518270806817,
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Issue 31's drag over 0.01/0.2/0 on the rod tapered to 0.3 with a point tip (the paper's
/// settings), to just past its slip at d = 0.118119: the side at s = 0.99991 that drives it peels
/// back to the tip 1.0e-5 into the slide, and the tip lies down again 1.4e-4 into it. Its energy
/// released, 0.0021184, was metered as 0.0020387 (3.8 % short: the rod jumped on by the slide's
/// λ at both changes, `driver_anchor`); every slip of the drag (3415) balances to 1e-8 now.
/// About 10 s in release: run on request (`--ignored`); the scenes above test the same change.
#[test]
#[ignore = "slow: 3415 slips, about 10 s in release"]
fn energy_balances_at_a_slip_whose_driver_peels_back_and_lies_down_again() {
    let c = Case {
        d_max: 0.1182,
        ..grid_case(0.01, 0.2, 0.0, 0.0)
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was open: the tip touches down sliding during a side's slip, and dissipated and released
/// differed by 8.7e-8. The energy balances to 1e-8 now that a round tip's slip is its place's
/// rate less its turn (watch.rs `fill_slip`: the work of a sliding round tip, and where it
/// halts, were counted from its contact point, which rolls).
#[test]
fn energy_balances_at_a_slip_where_a_round_tip_touches_down() {
    open(&Case {
        amp: 0.008166475071201208,
        wave: 0.05701275130979977,
        phase: 2.029454885395551,
        eta: 0.5410509006060614,
        mu_s: 0.56336598755007,
        ratio: 0.25468498610574397,
        taper: None,
        radius: 0.009511647163757388,
        d_max: 0.038226736892039315,
    });
}

/// Was open (found by the property at 64 cases from seed 21): a round tip that barely fits the
/// corrugation's valleys (r = 0.00947 against the radius of curvature 0.00978 under its crests,
/// so the rate `J` of its contact point is about 0.03 there) slipped 14 times; slips 0–11
/// balanced to 2e-12, slips 12 and 13 to 6.8e-7 and 1.7e-6 (of 5.9e-5 and 6.6e-5 released),
/// and at tol 5e-11 and below the drag ended in a solver failure locating slip 11's end (a
/// residual NaN). The disk's contact point was plain Newton, whose steps can leave the root's
/// bracket where `J` runs from 0.03 to 2 within it; kept in its bracket (`chain::disk_on_curve`)
/// it is found, and every slip balances to 7e-13 at tol 1e-10 and to 3e-13 at tol 1e-11 (the
/// program's `--energy-balance`, the slips at the same d to 1e-7).
#[test]
fn energy_balances_at_a_slip_of_a_round_tip_that_barely_fits_the_valleys() {
    open(&Case {
        amp: 0.007919774959433305,
        wave: 0.055290459623644594,
        phase: 0.0,
        eta: 0.7355787385222186,
        mu_s: 0.3,
        ratio: 0.2,
        taper: None,
        radius: 0.009468119971611235,
        d_max: 0.03,
    });
}

/// Was open (found by the property at 64 cases from seed 22): the rod tapered to 0.552 at
/// η 0.487 over a long corrugation (0.00547 sin(2πx/0.4046 + 0.234)) sticks from d = 0.064566
/// to 0.074054 before its slip 1224 (of 1227), a side lying down on the way; over that stick
/// the foot's work was 3.4e-8 more than the change of the rod's energy (of 8.6e-3 of work).
/// The work's quadrature refines a step by solving at its midpoints; two of them, in the last
/// step of the lying stretch, where the branch turns fast (μ rises by 0.01 within 1e-4 of d),
/// were refused by the march's branch test against the walk's newest point and the halves were
/// left unrefined. Predicted from the span's own ends and refused only at a fold or a jump
/// (`Stepper::correct_within`), every stick now balances to 1.9e-11 at worst.
#[test]
fn energy_balances_over_a_long_stick_of_a_tapered_rod() {
    open(&Case {
        amp: 0.005469627329621924,
        wave: 0.4046153483430688,
        phase: 0.23378081907949305,
        eta: 0.48733010809847677,
        mu_s: 0.3064713322595947,
        ratio: 0.294800235344426,
        taper: Some(0.5519428662989473),
        radius: 0.0,
        d_max: 0.09782418638952915,
    });
}

/// Was "nested slips 8 deep" (issue 31's texture grid, 0.01/0.05/4π/3, the uniform rod,
/// r = 0.005, the paper's drag settings): a side 0.025 behind the round tip and the tip took
/// turns at μs in slides of 2e-8 and 1e-8 that did not shrink, and the drag stopped at
/// d = 0.00126. With contacts that break free sliding together it reaches d_max (944 slips),
/// every contact by Coulomb and every slip's energy balance.
#[test]
fn a_side_and_a_tip_that_walked_in_turn_slide_together_to_d_max() {
    let c = Case {
        taper: None,
        ..grid_case(0.01, 0.05, 4.0 * std::f64::consts::PI / 3.0, 0.005)
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// A tip that slips beside a side 0.031 behind it that holds (texture grid: amplitude 0.001,
/// wavelength 0.5, phase 2π/3, taper 0.3, point tip): the rod between them is trapped, and its
/// force pair changes by ~1e8 per unit of the tip's slide. Natural steps failed on the slide's
/// first 5e-7 and the fold passage crawled 5000 steps without reaching it, through the side's
/// slip limit, so the drag stopped at d = 3.4e-6 ("the slide of such a tip is not followed").
/// The passage now hands its path back where an event has ended, and each of its points is the
/// rod at its own unknowns (they were watched on the shooter's paths of the passage's last
/// point): the drag reaches d_max, every contact by Coulomb and every slip's energy balance.
#[test]
fn a_tip_slipping_beside_a_side_on_a_steep_trapped_branch_slides_to_d_max() {
    let c = grid_case(0.001, 0.5, 2.0 * std::f64::consts::PI / 3.0, 0.0);
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// The scene of the test above one ulp away (phase `2·FRAC_PI_3`, 2.0943951023931957): the tip,
/// a passive slider in the stick before slip 1, halts at d = 0.2575587, where its slip rate is
/// 0 and the friction meter's `dN/dq = (dN/dλ)/(dq/dλ)` was infinite: the stick work before
/// slip 1 (d = 0.26156) read `inf` (record.rs `metered`). Every slip's and stick's energy fields
/// are finite and balance to 1e-8 now (measured: stick 1.4e-12, slips 2.7e-15), to d_max.
#[test]
fn the_stick_work_where_a_passive_slider_halts_is_finite() {
    let c = grid_case(0.001, 0.5, 2.0 * std::f64::consts::FRAC_PI_3, 0.0);
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was open: a solver failure at d = 0.00189 (locating the slip event, the corrector crossed a
/// fold). A side that formed sliding 0.0054 from the tip slid along in the tip's slip, and held
/// where the slip ended it trapped the rod between them in an equilibrium singular to working
/// precision (the Newton matrix's determinant 1e-27, of noisy sign; the tangential forces
/// changing by 1e8 per unit d): the next stick's first step passed both slip limits and none was
/// located. The side now slides on in the stick as it slid (drag.rs `sliding_on`). Until
/// 2026-12-02 it halted at d = 0.0020794, where holding it makes that singular state again, and
/// the drag stopped there by name (march.rs `halted_trapped`); that halt is at the slip rate's
/// noise (within 1e-7 at both ends of its step), and such a halt into a trapped, singular state
/// is not taken now (march.rs `Flow::Quiet`): the side slides on at a rate of zero, and the drag
/// reaches d_max through 33 slips, every contact by Coulomb and every slip's energy to 1e-8.
/// Which of its outcomes the drag takes is decided by rounding, not by the model: the side
/// touches down at d 0.0012773 beside the stuck tip in a trapped state, and the new state's
/// tangent there is the pair's nearly indeterminate tangential forces (dT/dd ~ 1e8) with a
/// normal part of either sign (+2.2e3 with the moving ends' derivatives by differences, −1.5e3
/// with them exact), which decides whether the side forms sliding or held. Before 2026-12-04
/// (differences) the drag reached d_max through 33 slips at tol 1e-10, 31 at 3e-11, 32 at
/// 1e-12 (the slips after the first at other places), and jammed at d 0.0016907 at 1e-11; since
/// (exact) it jams there at 1e-10. What is determined, and asserted: no solver failure, a
/// physical stop (d_max or that jam), every row checked (the harness's `check`).
#[test]
fn a_side_trapped_beside_the_tip_ends_by_a_physical_stop() {
    let c = Case {
        amp: 0.009263757406870549,
        wave: 0.25968873883664656,
        phase: 1.6908820380280873,
        eta: 0.5793521109513871,
        mu_s: 0.5539352966826757,
        ratio: 0.20947668408970366,
        taper: None,
        radius: 0.0,
        d_max: 0.08820531773788857,
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    let jam = out.contains("stopped: jam") && (stop_d(&out).unwrap() - 0.0016907).abs() < 1e-6;
    assert!(out.ends_with("stopped: d_max reached") || jam, "{out}");
}

/// Was open: a solver failure at d = 0.0603: the free rod's clearance jumped from -7.4e-5 to
/// 3.7e-12 (a maximum of the gap born beside the last side, past the sine's inflection). The
/// side begins to lie along the surface at d = 0.060243 (x = 0.428598, an inflection): the drag
/// stops there by name.
#[test]
fn a_touchdown_clearance_jump_was_a_side_beginning_to_lie() {
    open(&Case {
        amp: 0.017448889539086077,
        wave: 0.49069960664669376,
        phase: 3.936780989398785,
        eta: 0.7425894318714846,
        mu_s: 0.3,
        ratio: 0.2,
        taper: Some(0.348578600508169),
        radius: 0.0,
        d_max: 0.08420661735723857,
    });
}

/// Was open (the survey's case 63 is this scene): a stuck side lay 4.7e-10 beyond μs N
/// (N = 1.30) at the start of slip 5 (d = 0.0643905). The side alone reaches its slip limit
/// there, beside a round tip that holds; the rod trapped between them carries the shot's
/// rounding amplified to ~1e-8 in its forces, so the located point's step-backs, doubling from
/// a secant step of that noise (~1e-14), ended 4e-12 back after eight, still beyond. They go on
/// doubling now (events.rs `inside`): the ninth, 8e-12 back, is inside. The drag reaches d_max
/// (26 slips), every contact by Coulomb and every slip's energy to 1e-8.
#[test]
fn a_side_at_its_slip_limit_beside_a_held_round_tip_is_located_inside_it() {
    let c = Case {
        amp: 0.017564793381039036,
        wave: 0.2189514668211504,
        phase: 2.6805420607236523,
        eta: 0.6483859256163235,
        mu_s: 0.5269970455538149,
        ratio: 0.6796502871619943,
        taper: None,
        radius: 0.0020137422515238237,
        d_max: 0.07097660863330688,
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was a failure of this harness, not of the drag (the property's seed 11): a side lying on the
/// surface as a short stretch (to 1.2e-3 beyond its inner end) holds at a slip's row with its
/// resultant's `T/N` 0.30001 under μs 0.3, which the point contact's law `|T| ≤ μs N` refused.
/// Its friction law is the ratio it needs, `ContactState::friction_ratio` (part of its `T` the
/// surface's curvature takes up without friction), which the harness now checks ([`friction`]):
/// the drag passes, with a stuck stretch beyond `T = μs N` on a row and within its ratio.
#[test]
fn a_held_stretch_is_judged_by_the_friction_ratio_it_needs() {
    let c = Case {
        amp: 0.012007738743407414,
        wave: 0.4918497915532884,
        phase: 2.4041050054045603,
        eta: 0.5113063958361641,
        mu_s: 0.3,
        ratio: 0.2,
        taper: Some(0.3),
        radius: 0.0,
        d_max: 0.03,
    };
    open(&c);
    let r = drag_case(&c);
    let beyond =
        r.rows.iter().flat_map(|w| &w.contacts).find(|k| {
            k.hold == Hold::Stuck && k.lies_to.is_some() && k.tangential > c.mu_s * k.normal
        });
    let k = beyond.expect("a stuck stretch beyond T = mu_s N");
    let ratio = k.friction_ratio.unwrap();
    assert!(ratio.abs() <= c.mu_s, "{k}");
}

/// Was a solver failure (the property's seed 11, shrunk): a side walked slip by slip up to the
/// lying stretch, the rod between them lying ever closer along the surface (the surface's arc and
/// the rod's length between them 2.6e-11 apart at 7.1e-4 into the slip at d 0.0615607, 3.8e-14
/// at 1.09e-3), where the state is singular with that gap: "the branch is not resolved by
/// arclength steps down to 1.2e-10" on 11 output points. On 201 the slip ended at μk with the
/// gap at 1.4e-14, and the stick after it placed a fold by the output grid. From 2026-12-01 the
/// drag ended where the gap comes within `CLOSED` (`Crossing::Close`), by name ("a lying stretch
/// that takes in a side ... is not in the model"), in the slip at d 0.0602823, after 332. Since
/// 2026-12-02 the side and the stretch lie down there as one stretch from the side's place on
/// (events.rs `merged`), and the drag reaches d_max, checked, through the same slip on 11 and 21
/// output points.
#[test]
fn a_side_closing_up_to_a_lying_stretch_lies_down_with_it() {
    let c = Case {
        amp: 0.012007738743407414,
        wave: 0.4918497915532884,
        phase: 2.4041050054045603,
        eta: 0.5113063958361641,
        mu_s: 0.40346359778614144,
        ratio: 0.7216505954322054,
        taper: Some(0.45923951221585113),
        radius: 0.0,
        d_max: 0.0964825884322871,
    };
    let at = merges_on_grids(&c, &scene(&c), &[11, 21], 0.0602823);
    assert!((at[0].0 - at[1].0).abs() <= 1e-8, "{at:?}");
}

/// The drag of the case `c` on the harness's 11 output points, its rows to read (unchecked: a
/// test checks it with [`run`] first).
fn drag_case(c: &Case) -> DragResult {
    let (rod, surface) = scene(c).parts().unwrap();
    let o = DragOptions {
        d_max: c.d_max,
        points: 11,
        mu_s: Some(c.mu_s),
        mu_k: Some(c.ratio * c.mu_s),
        ..DragOptions::default()
    };
    drag(&rod, &surface, &o).unwrap()
}

/// The paper's drag settings (η 0.75, μs 0.5, μk 0.3, d_max 0.3) over `A sin(2πx/W + P)` on
/// the rod tapered to 0.3 (issue 31's texture grid).
fn grid_case(amp: f64, wave: f64, phase: f64, radius: f64) -> Case {
    Case {
        amp,
        wave,
        phase,
        eta: 0.75,
        mu_s: 0.5,
        ratio: 0.6,
        taper: Some(0.3),
        radius,
        d_max: 0.3,
    }
}

/// Was a solver failure (issue 31's texture grid, taper 0.3, point tip): at 0.01/0.5/4π/3 "the
/// height of the free rod above the surface jumps from -1.872e-5 to 5.574e-11 at d = 0.00658",
/// at 0.001/0.5/4π/3 "touchdown (side to side+side): the new contact state does not hold: Newton
/// did not converge (iteration 12, residual 6.4e-11)", at 0.001/0.2/4π/3 a jump again; then a stop
/// by name, "begins to lie along the surface". The side contact, the last one, rolls back to the
/// corrugation's steepest point; the rod beyond it is unloaded and straight (curvature 0), so the
/// gap's curvature there is the surface's alone and falls to zero at the surface's inflection,
/// where the straight end would cut the surface beside the contact (the event `Lie`). Since
/// 2026-11-30 the rod lies down along the surface there (a stretch, docs/model.md): each drag
/// lies down where the contact reaches an inflection of the sine, `2πx/W + P = kπ` (to 1e-9),
/// follows the stretch with every contact on the surface, pushing and by Coulomb, and reaches
/// d_max.
#[test]
fn a_side_reaching_the_corrugations_inflection_lies_down() {
    for (amp, wave) in [(0.01, 0.5), (0.001, 0.5), (0.001, 0.2)] {
        let c = grid_case(amp, wave, 4.0 * std::f64::consts::FRAC_PI_3, 0.0);
        let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        assert!(out.contains("stopped: d_max reached"), "{c:?}: {out}");
        let r = drag_case(&c);
        let lie = r
            .rows
            .iter()
            .position(|q| q.event == Some(DragEvent::Contact(Event::LieDown)))
            .unwrap_or_else(|| panic!("{c:?}: no lie-down in {r}"));
        let x = r.rows[lie].contacts.last().unwrap().x;
        let turns = (std::f64::consts::TAU * x / c.wave + c.phase) / std::f64::consts::PI;
        let off = (turns - turns.round()).abs() * c.wave / std::f64::consts::TAU;
        assert!(
            off <= 1e-9,
            "{c:?}: x = {x} lies {off:.2e} from an inflection"
        );
        assert_eq!(r.rows[lie + 1].contact.name(), "stretch", "{c:?}");
    }
}

/// Was "the stuck state after a slip: Newton did not converge (iteration 4, residual 4.063e2)"
/// (issue 31's texture grid, 0.01/0.05/2π/3 on the short rat preset, tip radius 0.005): the side
/// that drove a slip let go (N = 0) while the slip still needed a tangential force of 0.014
/// there, and the march took that for a lift-off (march.rs `released_pushing` now names such a
/// release a jam). Since a contact that breaks free in a slip slides along (drag.rs
/// `slide_driver`), the slip takes another path: the drag ends with a jam at the same slip
/// (d = 0.010963), where the free rod would cross the surface and no state continues. Every
/// contact of every row and slip up to there is on the surface, pushing and by Coulomb, and every
/// slip's and stick's energy balances (slip 13, where the tip slipped in turn inside the side's
/// slip, metered 5.28e-5 against 5.72e-5 released before).
#[test]
fn a_rat_slip_whose_side_let_go_jams_with_every_slip_balanced() {
    let c = Case {
        phase: 2.0 * std::f64::consts::FRAC_PI_3,
        taper: None,
        ..grid_case(0.01, 0.05, 0.0, 0.005)
    };
    // (run_in checks every row's and slip's contacts and every slip's and stick's energy)
    let out = run_in(&c, on_rat(&c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.contains("stopped: jam at"), "{out}");
}

/// The case's surface, heights and friction on the short rat preset (`data/scenes`).
fn on_rat(c: &Case) -> Scene {
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_short.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let rat: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    Scene {
        stiffness: rat.stiffness,
        precurvature: rat.precurvature,
        ..scene(c)
    }
}

/// The `d` of a stop in `run_in`'s words (`None`: d_max reached).
fn stop_d(out: &str) -> Option<f64> {
    let stop = out.split("stopped: ").nth(1)?;
    let d = stop.split("at d = ").nth(1)?;
    d.split([':', ' ', ',']).next()?.parse().ok()
}

/// The drag of the case `c` over `s` on each of `grids` output points, checked ([`run_checked`]:
/// every contact on the surface, pushing and by Coulomb, every slip balanced), must reach d_max
/// through the slip at `at` (to 1e-6) where a side, sliding, closes up to its neighbour: the two
/// lie down there as one stretch (a `lie_down` row in that slip, the row after it with the
/// stretch and one contact fewer). Each grid's place of that lie-down and its slips.
fn merges_on_grids(c: &Case, s: &Scene, grids: &[usize], at: f64) -> Vec<(f64, usize)> {
    grids
        .iter()
        .map(|&points| {
            let (out, r) = run_checked(c, s.clone(), points, HANG)
                .unwrap_or_else(|e| panic!("{points}: {c:?}: {e}"));
            assert!(out.ends_with("stopped: d_max reached"), "{points}: {out}");
            let r = r.unwrap();
            let i = (r.rows.iter())
                .position(|q| {
                    q.event == Some(DragEvent::Contact(Event::LieDown)) && (q.d - at).abs() < 1e-6
                })
                .unwrap_or_else(|| panic!("{points}: no lie-down at d = {at}: {out}"));
            let (before, after) = (&r.rows[i], &r.rows[i + 1]);
            // (two contacts, one of them a side, become one stretch)
            assert!(
                after.contacts.iter().any(|k| k.lies_to.is_some()),
                "{points}: {after:?}"
            );
            assert_eq!(
                after.contacts.len() + 1,
                before.contacts.len(),
                "{points}: {before:?} / {after:?}"
            );
            (before.d, r.slips.len())
        })
        .collect()
}

/// Was "the contact state side does not hold beyond d = 0.01977: the height of the free rod
/// above the surface (it would cross it) = 1.398e-5 after the change ... the model has no contact
/// state that continues" (issue 31's texture grid, 0.001/0.2/4π/3 on the short rat preset, point
/// tip): in the side's slip the free tip dipped below the corrugation and came back within one
/// step of the slide (0 to 0.01), so only the end of the slip (at 0.00312, the tip 1.6e-5 inside
/// the surface) was seen, and the next stick started crossing the surface. An event that holds
/// at a step's end but has ended at the earliest event located in it is now located before that
/// event (march.rs `dipped`): the tip touches down at 0.00108 of the slide. Further on, a
/// sliding tip that lies down in a slip (d = 0.026316) kept no slide (it became a rolling side,
/// and the stretch to the sliding side 0.027 away was trapped: a fold, "the slip does not end
/// quasi-statically"); it slides on with its ratio now (events.rs `kept_sliding`). Every contact
/// up to the stop is on the surface, pushing and by Coulomb, and every slip and stick balances.
#[test]
fn a_tip_dipping_below_the_texture_inside_a_slip_step_touches_down() {
    let c = Case {
        taper: None,
        ..grid_case(0.001, 0.2, 4.0 * std::f64::consts::FRAC_PI_3, 0.0)
    };
    // (to d = 0.027: further on, at 0.027221, the tip turns into the surface after a change, a
    // state the model does not continue, an open stop of the texture grid)
    let c = Case { d_max: 0.027, ..c };
    let out = run_in(&c, on_rat(&c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(!out.contains("no contact state"), "{out}");
    assert!(!out.contains("does not end quasi-statically"), "{out}");
    // (past the slip whose tip lies down, which starts at d = 0.0263165)
    assert!(stop_d(&out).is_none_or(|d| d > 0.026317), "{out}");
}

/// Was a solver failure at d = 0.0704 (issue 31's texture grid, 0.05/0.2/0 on the short rat
/// preset, tip radius 0.005): "locating the Slip(1) event: no sign change (f = 1.16e-3 and
/// 1.16e-3)". In the side's slip before, the stuck tip went past its slip limit and back within
/// one step of the slide, so the slip ended with the tip needing 1.16e-3 more than mu_s N, and
/// the next stick started beyond its own event. The tip's slip limit is now located inside the
/// slide (march.rs `dipped`; it breaks free and slides along), and the drag reaches d_max past
/// it, every contact by Coulomb and every slip and stick balanced.
#[test]
fn a_tip_passing_its_slip_limit_inside_a_slip_step_breaks_free() {
    let c = Case {
        taper: None,
        d_max: 0.08,
        ..grid_case(0.05, 0.2, 0.0, 0.005)
    };
    let out = run_in(&c, on_rat(&c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was "the contact state side+tip does not hold beyond d = 0.29591: |T| - mu0 N of contact 1
/// (it would slip) = 4.962e-4 after the change ... the model has no contact state that
/// continues" (issue 31's texture grid, 0.003/0.1/4π/3 on the short rat preset, tip radius
/// 0.005): a side touched down beside the tip needing 0.497 of its normal force as it formed and
/// 0.53 at the end of the first step, and its slip limit, pending at the first point (its forces
/// the solver's noise there), was taken for a state that does not hold. That step is now taken
/// again, shorter (march.rs `formed_too_long`): the side slips at d = 0.296004, and the drag
/// reaches d_max, every contact by Coulomb and every slip and stick balanced.
#[test]
fn a_side_that_forms_holding_and_slips_in_the_first_step_slips() {
    let c = Case {
        taper: None,
        ..grid_case(0.003, 0.1, 4.0 * std::f64::consts::FRAC_PI_3, 0.005)
    };
    let out = run_in(&c, on_rat(&c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was a solver failure (issue 31's texture grid, the rod tapered to 0.3, point tip): at
/// 0.001/0.02/0 "after d = 0.0085553: natural step: Newton did not converge (iteration 12,
/// residual NaN); pseudo-arclength: residual 1.9e-12", at 0.001/0.02/4π/3 the same after
/// d = 0.0028063. A side that creeps (slides with μk beside a side that holds, one wavelength
/// behind it) loses its normal force, and its slip rate (about 2.6e-5 N) falls to zero with it:
/// the halt was located at a root of the solver's noise (N = 7.4e-7, 1.7e-8 in d before the
/// side's own lift-off, at phase 0), and the held side needed |T|/N of 23 at once, on a branch
/// no natural step followed. A halt within the smallest natural step of the contact's own
/// lift-off is that lift-off now (march.rs `shadows`): the side lets go at N = 0, after the
/// point where the drag failed, every contact by Coulomb and every slip and stick balanced up
/// to a named stop. (Both go on to jams at d = 0.015402 and 0.010295, with the program's 201
/// output points and with this test's 11: see the test below.)
#[test]
fn a_creeping_side_that_halts_as_it_lets_go_is_released() {
    let third = 4.0 * std::f64::consts::FRAC_PI_3;
    creeping_scenes_stop_beyond([(0.0, 0.008555276994325253), (third, 0.002806274949312679)]);
}

/// The drags over 0.001/0.02 (taper 0.3, point tip) at the phases of `bounds`, each checked
/// by [`run`] and stopping (if before d_max) beyond its bound.
fn creeping_scenes_stop_beyond(bounds: [(f64, f64); 2]) {
    for (phase, bound) in bounds {
        let c = grid_case(0.001, 0.02, phase, 0.0);
        let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        assert!(stop_d(&out).is_none_or(|d| d > bound), "{c:?}: {out}");
    }
}

/// Was open: after the release above (0.001/0.02/0 and 4π/3, taper 0.3, point tip) the first
/// step with this test's 11 output points is 0.01 long, and the free rod where the side let go,
/// which leaves the surface and touches down again 1.3e-3 further on, lay across it at the
/// step's end: "the contact state side does not hold" at the release. The foot's first step
/// after a change is now taken again, shorter, where the free rod crossed the surface elsewhere
/// inside it (march.rs `check_pending`): both drags go on past the release, to the jams the
/// program's 201 points reach.
#[test]
fn a_released_side_touching_down_again_inside_the_first_step_is_followed() {
    creeping_scenes_stop_beyond([
        (0.0, 0.0085553),
        (4.0 * std::f64::consts::FRAC_PI_3, 0.0028063),
    ]);
}

/// Was open: the same cause on 0.003/0.05/0 (taper 0.3, point tip) was "after d = 0.035075:
/// Newton did not converge (residual 1.1e-8); locating the fold: residual 4.8e-12", a creeping
/// side that halted 1.7e-8 before its lift-off; released there, the drag goes on through some
/// 3000 slips. It failed further on, at d = 0.050025: in a slip the free rod touches down one
/// wavelength (0.05) beyond the sliding side, on the next crest, and the fold passage wrote a
/// fold row there whose new side had N = 0 and T = -1.7e-4, beyond Coulomb. The stretch of rod
/// between the two sides is straight and unloaded, and both hold without slip: pulled along its
/// length it does not bend, so at N = 0 any pair of opposite tangential forces at its ends is
/// an equilibrium (the new state's Jacobian singular, det -1.3e-17), and the branch on which the
/// new side loads leaves that line at T = -1.7e-4. Such a side slides from the start, the way
/// the rod moves over it (march.rs `formed_holds`): here with the driver, at +μk, its N
/// rising at 34 per unit slide. The drag goes on through some 6000 slips to a named jam at
/// d = 0.1120, every row and slip checked. About 30 s of CPU in release.
#[test]
#[ignore = "slow: about 6000 slips, 30 s of CPU in release"]
fn a_side_touching_down_at_the_end_of_a_straight_trapped_stretch_slides() {
    let c = grid_case(0.003, 0.05, 0.0, 0.0);
    if let Err(e) = run_bounded(&c, scene(&c), 11, SLOW_HANG) {
        panic!("{c:?}: {e}");
    }
}

/// Was a solver failure (issue 31's texture grid, 0.05/0.5/4π/3 on the uniform rod, point tip):
/// "after d = 0.012947: during a slip: natural step to 0.000657: Newton did not converge
/// (iteration 0, residual NaN)". In the slip the driving side rolls to the tip; the height of
/// the free end beyond it vanishes with that end, and a touchdown of the tip was located 1.8e-12
/// of the slide before the peel-back: the set side (s = 1 − 1.5e-12) + tip had crossing contacts
/// at the first step. A touchdown of the free end within the smallest natural step of a side's
/// peel-back to the tip is that peel-back now (march.rs `shadows`), and the drag goes on past
/// that slip, every contact by Coulomb and every slip and stick balanced, to a named stop.
#[test]
fn a_tip_touching_down_as_the_side_rolls_onto_it_is_the_peel_back() {
    let c = Case {
        taper: None,
        ..grid_case(0.05, 0.5, 4.0 * std::f64::consts::FRAC_PI_3, 0.0)
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(stop_d(&out).is_none_or(|d| d > 0.012947), "{c:?}: {out}");
}

/// The short rat preset on `A sin(2πx/W + P)` (issue 31's texture grid) with a point tip.
fn rat_case(amp: f64, wave: f64, phase: f64, d_max: f64) -> (Case, Scene) {
    let c = Case {
        taper: None,
        d_max,
        ..grid_case(amp, wave, phase, 0.0)
    };
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_short.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let rat: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let s = Scene {
        stiffness: rat.stiffness,
        precurvature: rat.precurvature,
        ..scene(&c)
    };
    (c, s)
}

/// Was slow (issue 31's texture grid, 0.001/0.02/2π/3 on the short rat preset, point tip: 331
/// slips to d = 0.00073 in 87 s of CPU, 2600 Newton iterations a slip): the contact at s = 0.9964
/// slips beside a side at s = 0.9767 that holds, and the rod trapped between them relaxes the
/// driver from μs to μk over a slide of 4e-10, far inside the slide's shortest natural step
/// (5e-7). The fold passage took that step: 792 points to its end, 1090 Newton iterations,
/// where the march used the first four (μk holds the driver among them) and dropped the rest.
/// The passage now ends at the first point where an event of the march has ended (fold.rs
/// `pass`). Every row's and slip's contacts and energies are checked (run_in); the drag to
/// d = 1e-5 (two slips) takes fewer than 1000 Newton iterations in all, start included (2502
/// before, 346 now; to 3e-5, nine slips: 10245 before, 480 now).
#[test]
fn a_trapped_slides_fold_passage_ends_where_the_driver_sticks() {
    let (c, s) = rat_case(0.001, 0.02, 2.0 * std::f64::consts::FRAC_PI_3, 1e-5);
    let out = run_in(&c, s.clone()).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.contains("stopped: d_max reached"), "{out}");
    let (rod, surface) = s.parts().unwrap();
    let o = DragOptions {
        d_max: c.d_max,
        points: 11,
        mu_s: Some(c.mu_s),
        mu_k: Some(c.ratio * c.mu_s),
        energy_balance: true,
        ..DragOptions::default()
    };
    let r = drag(&rod, &surface, &o).unwrap();
    assert_eq!(r.slips.len(), 2, "{out}");
    let n = r.stats.newton_iters;
    assert!(n < 1000, "{n} Newton iterations: {out}");
}

/// Was "solver failure after d = 0.039386053748166464: natural step to 0.03938611238667263:
/// the branch turned by 179° over the step; locating the fold: Newton did not converge
/// (iteration 2, residual 1.414e-10)" (issue 31's texture grid, 0.001/0.2/4π/3 on the short
/// rat preset, point tip, once the touchdown forecast of 2026-12-01 had moved its steps): on the
/// thin tip the corrections on the fold's chord stall at a residual floor of ~1e-10 against the
/// tolerance 1e-12, and they are taken within a thousand tolerances (fold.rs `on_chord`). That
/// fold, at d 0.0393860 in the stick after the slip at 0.03938605, was placed by rounding: two
/// sides had closed up slip by slip, and in that slip the rod between them came within 1e-11 of
/// lying along the surface; on 11 and 51 output points the drag went past it (a slip more, then
/// those sides closing up at d 0.0426643), on 21 and 201 it stopped at the fold. With the
/// closing's threshold at 1e-11 (2026-12-01) the drag ended in that slip by name, the same on
/// every output grid; since 2026-12-02 the two sides lie down there as one stretch (events.rs
/// `merged`) and the drag goes on to d_max, checked, through that slip on every grid (d to 1e-8:
/// the slip's place).
#[test]
fn two_sides_closing_up_lie_down_as_one_stretch_on_every_grid() {
    // (the grid's phase, 4π/3 rounded as texture.py has it: the train of slips is chaotic)
    let (c, s) = rat_case(0.001, 0.2, 4.0 * std::f64::consts::PI / 3.0, 0.3);
    let at = merges_on_grids(&c, &s, &[201, 11, 51], 0.0393861);
    for e in &at[1..] {
        assert!((e.0 - at[0].0).abs() <= 1e-8, "{at:?}");
    }
}

/// Was "solver failure after d = 0.10621430237881183: locating the Slip(1) event: the branch
/// turned by 173° over the step" (issue 31's texture grid, 0.001/0.2/2π/3 on the short rat
/// preset, point tip, once the touchdown forecast of 2026-12-01 had moved its steps): natural steps
/// failed next to a fold, and the fold passage's first point, 2e-7 further in d, had passed the
/// side's slip limit; the search in `λ` through the last points met the branch turned back
/// and forth, and the same step then came from the passage each time (100 000 times, until the
/// step budget). The slip is now located on the passage's own step (fold.rs
/// `locate_on_chord`), and the drag goes on, every contact by Coulomb and every slip and stick
/// balanced. Its two sides close up slip by slip, the Newton matrix's smallest singular value
/// over its largest 5.7e-11, 1.7e-11, 4.0e-12, 6.1e-13, 3.7e-14 in the stuck states after the
/// slips at d 0.093 to 0.106; in the slip at d 0.1062127 the rod between them comes within 1e-11
/// of lying along the surface, where the drag ended by name from 2026-12-01 (on 201, 21 and 11
/// output points alike) and where the two lie down as one stretch since 2026-12-02: the drag
/// reaches d_max through that slip on every grid.
#[test]
fn a_slip_inside_a_step_of_the_fold_passage_is_located_on_it() {
    let (c, s) = rat_case(0.001, 0.2, 2.0 * std::f64::consts::PI / 3.0, 0.3);
    let at = merges_on_grids(&c, &s, &[201, 21, 11], 0.1062127);
    for e in &at[1..] {
        assert!((e.0 - at[0].0).abs() <= 1e-8, "{at:?}");
    }
}

/// Was "the contact state side+tip does not hold beyond d = 0.027221: -sin(phi(1) - beta) (the
/// tip would turn into the surface) = 5.297e-5 after the change ... the model has no contact
/// state that continues" (issue 31's texture grid, 0.001/0.2/4π/3 on the short rat preset, point
/// tip; 0.001/0.05/4π/3 and 0.001/0.2/2π/3 alike): a side sliding with kinetic friction in a
/// stick (the tip lay down sliding in a slip) reached the rod's end and peeled back to a tip
/// that held stuck, needing |T|/N = 46 there, and the tip then turned into the surface. It slides
/// on as the tip with its ratio (events.rs `kept_sliding`, as a tip that lies down does), and
/// the drag goes past d = 0.027221, every contact by Coulomb and every slip and stick balanced.
#[test]
fn a_sliding_side_that_peels_back_to_the_tip_slides_on() {
    let (c, s) = rat_case(0.001, 0.2, 4.0 * std::f64::consts::FRAC_PI_3, 0.03);
    let out = run_in(&c, s).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was "the contact state side does not hold beyond d = 0.0031115: the height of the free rod
/// above the surface (it would cross it) = 1.781e-5 after the change ... the model has no
/// contact state that continues" (issue 31's texture grid, taper 0.3, 0.003/0.02/4π/3, point
/// tip): a sliding side at s = 0.986 let go, and the free rod's height, zero there after the
/// release, was pending; the first step (to 0.0045) found it 1.8e-5 above zero, but at s = 0.946,
/// where the rod touched down inside the step while the released point rose. That step is now
/// taken again, shorter (march.rs `check_pending`), and the touchdown is located. To d = 0.01,
/// every contact by Coulomb and every slip and stick balanced. (Further on, at d = 0.0105, a
/// slip jams: a slip's driver that kinetic friction holds from the first point of a state where
/// another contact reversed.)
#[test]
fn a_touchdown_inside_the_first_step_after_a_release_is_located() {
    let c = Case {
        d_max: 0.01,
        ..grid_case(0.003, 0.02, 4.0 * std::f64::consts::FRAC_PI_3, 0.0)
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was "the contact state side does not hold beyond d = 0.236426: cos(phi - beta) kappa at
/// contact 1 (it would lie along the surface) = 4.172e-2 after the change ... the model has no
/// contact state that continues" (issue 31's texture grid, 0.02/0.5/0 on the short rat preset,
/// point tip): the tip turned tangent in a trough of the corrugation that curves more than the
/// rod's end, so the side it became lies along the surface from its first point. The stop was
/// then the lie's, by name, at the same d; since a side that begins to lie along the surface lies
/// down (a lying stretch, docs/model.md), the drag goes on to d_max (11 955 slips on the
/// library's 401 output points, as on the program's 201). (The drag alone: longer than `run_in`'s
/// HANG allows.)
#[test]
#[ignore = "slow: about 15 s in release, 11955 slips"]
fn a_tip_lying_down_in_a_trough_that_curves_more_than_its_end_lies_along() {
    let (c, s) = rat_case(0.02, 0.5, 0.0, 0.3);
    let (rod, surface) = s.parts().unwrap();
    let o = DragOptions {
        d_max: c.d_max,
        mu_s: Some(c.mu_s),
        mu_k: Some(c.ratio * c.mu_s),
        ..DragOptions::default()
    };
    let r = drag(&rod, &surface, &o).unwrap();
    assert_eq!(r.stop, StopReason::DMax, "stopped: {}", r.stop);
    assert!(r.slips.len() > 11000, "{} slips", r.slips.len());
}

/// Issue 31's own example, `vibrissa drag --eta 0.75 --mu-s 0.5 --mu-k 0.3 --d-max 0.3
/// --corrugation-amplitude 0.005 --corrugation-wavelength 0.05` (201 output points, as the
/// program's default): it ended after 3 slips, "contact change at d = 0.010511365: the contact
/// state tip does not hold beyond d = 0.010511365: -sin(phi(1) - beta) (the tip would turn into
/// the surface) = 4.992e-3 after the change ... the model has no contact state that continues".
/// In the third slip the sliding tip turned into the surface 3.0e-5 into the slide and out again
/// within the slide's first step (to 0.0029), so the slip ended, at 0.00167, with the rod's end
/// pointing 5.0e-3 into the surface; the tip's lying down is now located inside that step
/// (march.rs `dipped`, in a slip driven by the tip too), and the side it becomes slides on.
/// Every contact up to the stop is on the surface, pushing and by Coulomb, and every slip and
/// stick balances its energy.
#[test]
fn the_issues_example_slides_on_where_its_tip_lies_down_in_a_slip() {
    let c = Case {
        taper: None,
        ..grid_case(0.005, 0.05, 0.0, 0.0)
    };
    let out = run_points(&c, scene(&c), 201).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(!out.contains("no contact state"), "{out}");
    assert!(!out.contains("does not hold"), "{out}");
    // (past the third slip, which starts at d = 0.0105114)
    assert!(stop_d(&out).is_none_or(|d| d > 0.0105114), "{out}");
}

/// Issue 31's own example (as above) stopped after 5 slips at d = 0.016653, "the rod does not go
/// on quasi-statically (a snap): its equilibria fold back in the contact state side+tip with its
/// contact at s = 1.000000 pulling (N = -9.704e-6)". In the sixth slip, driven by the side at
/// s = 0.995928, the free tail beyond the side (unloaded, so straight) touches down at its end
/// 6.2e-4 into the slide. Held there, the tip makes a state singular to working precision:
/// rolling the side moves its point along the straight tail by as much as it shortens it
/// (march.rs `formed_holds`, which took only sides before). The tip now slides from the
/// start with kinetic friction; 1.4e-4 further on the side lets go with T = 0.154 still on it,
/// and the tip, held where it is then (march.rs `hold_riders`), needs 0.367 of its normal force:
/// it slides on as the slip's driver until μk holds it (drag.rs `still_sliding`). (Left sliding,
/// the tip jumped 3.8e-4 at once to the same end, and 3.3e-4 of the slip's 1.14e-3 released
/// energy was no friction work.) The drag reaches `d_max` (92 slips), every contact on the
/// surface, pushing and within Coulomb, every slip balancing its energy.
#[test]
fn the_issues_example_reaches_d_max_past_a_tip_touching_down_beyond_its_sliding_side() {
    let c = Case {
        taper: None,
        ..grid_case(0.005, 0.05, 0.0, 0.0)
    };
    let out = run_points(&c, scene(&c), 201).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was "the contact state side does not hold beyond d = 0.12101133565705371: the height of the
/// free rod above the surface (it would cross it) = 2.342e-3 after the change ... the model has
/// no contact state that continues" after 6990 slips (issue 31's texture grid, 0.001/0.05/4π/3
/// on the rod tapered to 0.3, point tip). In the last slip the side at s = 0.884767 drives, and a
/// side that touched down 0.05 beyond it slides along with kinetic friction; the driver's normal
/// force falls to zero (7.8e-14) with T = 0.1204 still on it. The slider, left free to move,
/// jumped at the release and the next stick started with the rod 2.3e-3 through the surface.
/// Held where it was (march.rs `hold_riders`), the rod without the driver still crosses the
/// surface, by 1.7e-5 at s = 0.884755, next to where the driver let go: no state without the
/// driver lies near, and with it its normal force would pull. The slip turns dynamic: a jam, at
/// the same d, after 6989 slips that each balance their energy (march.rs `released_pushing`).
#[test]
#[ignore = "slow: 6989 slips, about 30 s of CPU in release"]
fn a_driver_letting_go_while_it_pushes_beside_a_slider_is_a_jam() {
    let c = grid_case(0.001, 0.05, 4.0 * std::f64::consts::FRAC_PI_3, 0.0);
    let out = run_bounded(&c, scene(&c), 201, SLOW_HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(!out.contains("does not hold"), "{out}");
    assert!(
        out.contains("stopped: jam at") && out.contains("lets go"),
        "{out}"
    );
    let d = stop_d(&out).unwrap_or(f64::NAN);
    assert!((d - 0.1210113).abs() < 1e-6, "d = {d}: {out}");
}

/// Was "the contact state side+side does not hold beyond d = 0.2965843410172796: -N of contact 1
/// (it would pull) = 6.149e-3 after the change, and the state before it ended there: the model
/// has no contact state that continues" after 4852 slips (issue 31's texture grid, 0.003/0.1/4π/3
/// on the rod tapered to 0.3, point tip; the grid's one "does not hold"). In the stick after the
/// last slip the rod rests on one side, rolling at s = 0.884553 (|T|/N = 0.295), and the free rod
/// behind it touches down on the crest before, at s = 0.813845. Held there, the new side traps
/// the stretch between the two sides and would pull at once (on the held state's tangent
/// dN/dd = -14.6, dT/dd = 92.3), though the state without it crosses the surface: the new side
/// cannot hold, and it cannot stay off. It slides from the start (march.rs `formed_holds`):
/// towards +x with T = +μk N it loads (dN/dd = 4.3) and slips that way (5.9e-4 per unit d);
/// towards −x it would slip against its friction. The drag reaches `d_max`, every row's contacts
/// on the surface, pushing and within Coulomb, every slip balancing its energy. About 18 s of
/// CPU in release.
#[test]
#[ignore = "slow: 4852 slips, about 18 s of CPU in release"]
fn a_side_touching_down_that_would_pull_if_held_slides_from_the_start() {
    let c = grid_case(0.003, 0.1, 4.0 * std::f64::consts::FRAC_PI_3, 0.0);
    let out = run_bounded(&c, scene(&c), 201, SLOW_HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(!out.contains("does not hold"), "{out}");
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was a jam (issue 31's texture grid, 0.003/0.05/2π/3 on the short rat preset, tip radius
/// 0.005): "the slip cannot go on quasi-statically: the contact state side+side+tip does not hold
/// beyond 3.345804e-8 of the slip (|T| - mu0 N of contact 1 (it would slip) = 8.542e-1)" at
/// d = 0.0289109 (56 slips). In the 57th slip the tip slides towards −x beside a side held at
/// s = 0.983101, and 3.3e-8 into the slide the rod behind that side touches down at s = 0.936231.
/// Held there, the new side traps the stretch between the two sides and would pull at once
/// (dN = −318, dT = 5189 per unit slide on the held state's tangent), though the state without
/// it crosses the surface. It slides from the start with kinetic friction the way the rod moves
/// over it (march.rs `formed_holds`), towards +x, and loads; where μk holds the tip it sticks
/// with N = 1.07e-4, T/N = 0.3. The drag goes on past that slip (to d = 0.028911 here: the 57
/// slips in about 0.5 s of CPU in release), every row's contacts on the surface, pushing and
/// within Coulomb, every slip balancing its energy; the whole grid drag reaches `d_max` (5227
/// slips).
#[test]
fn a_contact_touching_down_in_a_slip_that_would_pull_if_held_slides_from_the_start() {
    let (c, s) = rat_case(0.003, 0.05, 2.0 * std::f64::consts::FRAC_PI_3, 0.028911);
    let c = Case { radius: 0.005, ..c };
    let s = Scene {
        tip_radius: 0.005,
        ..s
    };
    let out = run_in(&c, s).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(!out.contains("does not hold"), "{out}");
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// A survey of `PROPTEST_CASES` (else 100) scenes from proptest's deterministic seed, each
/// outcome printed (not stopping at the first failure): `cargo test -p vibrissa --test
/// contact_forces -- --ignored --nocapture survey`.
#[test]
#[ignore = "a survey: prints every scene's outcome"]
fn survey() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let n = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let mut runner = TestRunner::deterministic();
    let (mut failed, mut rejected) = (0, 0);
    for i in 0..n {
        let c = cases().new_tree(&mut runner).unwrap().current();
        println!("case {i}: {c:?}");
        let t0 = std::time::Instant::now();
        let out = std::panic::catch_unwind(|| run(&c));
        let secs = t0.elapsed().as_secs_f64();
        let verdict = match out {
            Ok(Ok(what)) => format!("ok: {what}"),
            Ok(Err(TestCaseError::Reject(why))) => {
                rejected += 1;
                format!("rejected: {why}")
            }
            Ok(Err(e)) => {
                failed += 1;
                format!("FAIL {e}")
            }
            Err(_) => {
                failed += 1;
                "PANIC".to_string()
            }
        };
        println!("case {i} ({secs:.2} s): {verdict}");
    }
    println!("{failed} of {n} failed, {rejected} rejected");
}

/// Was "slip 3 at d = 0.06383052881053361, after: sliding tip ... off dir mu_k N by 1.260e-4"
/// (the property's seed 6): in a slip the tip, touching at N = 1.5e-3 beside a side that holds at
/// N = 1.7, relaxes from μs to μk over a slide shorter than the slide's rounding, and the slip's
/// end was recorded where the search ended, at `T = μs N`, though labelled sliding with μk. A
/// slide end that misses μk by more than 1e-6 of N is solved again as the exact kinetic state
/// (drag.rs `located_kinetic`): the tip slides on at `T = μk N` (0.5620 N, the side's
/// tangential force 1.5e-4 higher), every contact by Coulomb and every slip and stick balanced,
/// to d_max after 446 slips.
#[test]
fn a_tip_barely_touching_beside_a_side_ends_its_slip_on_kinetic_friction() {
    let c = Case {
        amp: 0.01936533817462032,
        wave: 0.29895571757596795,
        phase: 1.3908537771965517,
        eta: 0.7186171049982287,
        mu_s: 0.6475517052227714,
        ratio: 0.8678299279025635,
        taper: Some(0.4791677121529978),
        radius: 0.0,
        d_max: 0.07460472634790609,
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.starts_with("906 rows, 446 slips"), "{out}");
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was a solver failure on 11 output points (the texture grid's scene on the grid of the drag
/// property; the grid's 201 points reach d_max): the short rat preset at η 0.75 over
/// 0.02 sin(2πx/0.5) (μs 0.5, μk 0.3) stopped at d 0.24485 after 11 950 slips with "touchdown
/// (side to side+tip): the new contact state does not hold: Newton did not converge (iteration
/// 7, residual NaN)". Its tip had turned tangent and become a side 1.8e-5 before the tip; a step
/// of 0.01 ended with the free tail in the surface further in, and the touchdown's search
/// returned a point where the tail's end is 5.6e-11 above the surface (the clearance's noise),
/// in a singular state. The step is now taken again shorter (march.rs `after_step`), which
/// meets no touchdown there: the drag reaches d_max with as many slips as the texture grid's
/// row of the scene on 201 points (`data/drag/texture_grid.csv`; their places agree to 1.7e-9).
/// 18 s in the test profile.
#[test]
fn a_touchdown_in_the_noise_of_a_long_step_is_taken_again_shorter() {
    let (_, scene) = rat_case(0.02, 0.5, 0.0, 0.3);
    let (rod, surface) = scene.parts().unwrap();
    let o = DragOptions {
        d_max: 0.3,
        points: 11,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        ..DragOptions::default()
    };
    let r = drag(&rod, &surface, &o).unwrap();
    assert_eq!(r.stop, StopReason::DMax, "{}", r.stop);
    let grid = format!(
        "{}/../../data/drag/texture_grid.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let grid = std::fs::read_to_string(grid).unwrap();
    let row: Vec<&str> = (grid.lines())
        .find(|l| l.starts_with("0.02,0.5,0,rat_short,0,"))
        .unwrap()
        .split(',')
        .collect();
    assert_eq!(row[6], "d_max");
    assert_eq!(r.slips.len(), row[7].parse::<usize>().unwrap());
}

/// Was "the sliding contact at s = 1.000000 halts and holds where it is: the state side+tip then
/// traps the rod …" (issue 31's texture grid, the uniform rod over 0.05/0.5/4π/3, point tip, at
/// d 0.08279 after 38 slips). A tip formed sliding beside a side at a slip's end slid at a rate
/// of 1.3e-9 to 1.5e-10 (noise: it does not move), and halted at that noise's sign change
/// 5.8e-5 before its own lift-off, into a state that traps the rod. A halt is no longer located
/// for a contact that lifts off within the step while its slip rate is within 1e-7 at both
/// ends (march.rs `noise_halt`): on the grid's 201 output points the drag reaches d_max, every
/// contact by Coulomb and every slip's energy balance. On this harness's 11 points it still
/// halted, at d 0.0847 after 39 slips, of a contact that does not lift off within that step: a
/// halt at the rate's noise whose held state traps the rod, singular to working precision, is
/// now not taken either (the step again, that contact's noise halts not located: march.rs
/// `Flow::Quiet`), and on 11 points the drag reaches d_max through the 110 slips of 201.
#[test]
fn a_slider_whose_rate_is_noise_does_not_halt_into_a_trap() {
    let c = Case {
        taper: None,
        ..grid_case(0.05, 0.5, 4.0 * std::f64::consts::PI / 3.0, 0.0)
    };
    for points in [201, 11] {
        let out = run_points(&c, scene(&c), points).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        assert!(out.ends_with("stopped: d_max reached"), "{points}: {out}");
        assert!(out.contains(" 110 slips,"), "{points}: {out}");
    }
}

/// The same on the output grid of this harness (11 points) for the uniform rod over
/// 0.01/0.1/0: the tip's rate had one sign of its noise on 201 points (d_max) and the other on
/// 11 (the trapped halt at d 0.01533 after 6 slips). Here to d 0.05.
#[test]
fn a_noise_halt_does_not_depend_on_the_output_grid() {
    let c = Case {
        taper: None,
        d_max: 0.05,
        ..grid_case(0.01, 0.1, 0.0, 0.0)
    };
    let out = run(&c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// The short rat preset over 0.02 sin(2πx/0.5 + 2π/3) (issue 31's texture grid) on this
/// harness's 11 output points: it stopped where its tip halts at the rate's noise into a trapped
/// state (d 0.0685), and since that halt is not taken
/// (`a_slider_whose_rate_is_noise_does_not_halt_into_a_trap`) it slid on, and at d 0.0746456
/// its tip touched down 0.0016 beyond a side whose curvature had come to the surface's. The
/// side lay along the surface from that state's first point, and the stretch it formed did not
/// hold there (Newton stalled at a residual of 1.6e-7): the drag ended there by the lie's name,
/// not as a solver failure, and without the row of the state that did not go on (its tip
/// pulled, N = −0.067). On the program's 201 points the tip did not touch down there, the side
/// lay down at d 0.0758818, and the drag reached d_max (45 slips). Since the moving ends'
/// derivatives are exact (2026-12-04) the drag reaches d_max on the 11 points too, through 45
/// slips, every row checked and every slip balanced (the harness's `check`).
#[test]
fn the_short_rat_preset_over_a_steep_sine_reaches_d_max_past_its_lie_down() {
    let (c, s) = rat_case(0.02, 0.5, 2.0 * std::f64::consts::PI / 3.0, 0.3);
    let out = run_in(&c, s).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    assert!(out.ends_with("stopped: d_max reached"), "{out}");
}

/// Was open (the property's seed 25 at 64 cases, found 2026-12-02): at d = 0.0537674 in a stick
/// a side touches down at s = 0.99707 (N = 0) beside a side at s = 0.90324 that slides with
/// N = 4.9e-12, a force at the rounding of the stuck side's 5.6. That slider halts (its rate's
/// sign flips at the same instant), and the first point of the state its halt leads to, the row
/// of the next halt there, had the new side at N = −3.5e-13; the two then let go, one after
/// the other, 2e-14 further in d. A normal force that close below zero at a state's first point
/// is zero (march.rs `at_zero`, the rule for an event function right after a change of set),
/// and the row says so; the drag goes on as before, to its jam at d 0.0613862. Whether it goes
/// on past that halt is decided by rounding: with the moving ends' derivatives by differences
/// (before 2026-12-04) the drag jammed at d 0.0613862 at tol 1e-10 and 3e-11 (56 and 21 slips
/// on the program's 11 points) and ended at the halt at 1e-11 (the state after it pulls at a
/// side, N = −0.18: a contact change), with them exact the other way round. Asserted: a
/// physical stop at the halt or beyond, every row checked, none tensile.
#[test]
fn a_halt_among_contacts_at_rounding_level_forces_is_not_tensile() {
    let c = Case {
        amp: 0.006015803849262808,
        wave: 0.09383009718044578,
        phase: 5.715338255326185,
        eta: 0.5030551739420375,
        mu_s: 0.7114716298873875,
        ratio: 0.297346301291451,
        taper: Some(0.7017575271653013),
        radius: 0.0,
        d_max: 0.09164927359441077,
    };
    let out = run_in(&c, scene(&c)).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    let d = stop_d(&out).unwrap_or(f64::NAN);
    let jam = out.contains("stopped: jam") && (d - 0.0613862).abs() < 1e-6;
    let halt = out.contains("stopped: contact change") && (d - 0.0537674).abs() < 1e-6;
    assert!(jam || halt, "{out}");
}

/// The texture grid's uniform rod, point tip, over 0.003/0.02 at `phase` to `d_max` (the paper's
/// drag settings, as [`grid_case`]).
fn fine_uniform(phase: f64, d_max: f64) -> Case {
    Case {
        taper: None,
        d_max,
        ..grid_case(0.003, 0.02, phase, 0.0)
    }
}

/// Was a named stop at d = 0 (issue 31's texture grid, the uniform rod over 0.003/0.02 at phases
/// 0 and 2π/3, point tip): pressed without friction, the rod touches at a side 0.0097 (0.0101)
/// before the tip, and with both held the pair of tangential forces between them is
/// indeterminate, the equilibrium singular to working precision ("the point-contact model does
/// not resolve it"). In a drag the contact of the pair with the least normal force slides from the
/// start with kinetic friction, the way its state slips it (march.rs `slides_at_start`): the same
/// rod, the foot's force unchanged, the split the one friction fixes. Each drag reaches d_max,
/// every row on the surface, pushing and by Coulomb, every slip balanced, with the same slips
/// on 201 and 11 output points (918 and 429 to d 0.3).
#[test]
fn a_drag_whose_start_traps_an_indeterminate_pair_slides_from_it() {
    // (the contact with the least normal force in the frictionless press: the tip at phase 0,
    // the side at 2π/3)
    for (phase, slips, tip) in [
        (0.0, 918, true),
        (2.0 * std::f64::consts::PI / 3.0, 429, false),
    ] {
        let c = fine_uniform(phase, 0.3);
        for points in [201, 11] {
            let (out, r) = run_checked(&c, scene(&c), points, HANG)
                .unwrap_or_else(|e| panic!("{c:?} on {points}: {e}"));
            let r = r.expect("a start");
            assert_eq!(r.stop, StopReason::DMax, "{out}");
            assert_eq!(r.slips.len(), slips, "{out}");
            let start = &r.rows[0];
            assert_eq!(start.d, 0.0);
            assert_eq!(start.contacts.len(), 2, "{out}");
            let sliding = |k: &&ContactState| matches!(k.hold, Hold::Sliding { .. });
            let slid: Vec<_> = start.contacts.iter().filter(sliding).collect();
            let held: Vec<_> = start.contacts.iter().filter(|k| !sliding(k)).collect();
            assert_eq!((slid.len(), held.len()), (1, 1), "{out}");
            assert_eq!(slid[0].tip, tip, "{out}");
        }
    }
}

/// The drag of the test above at phase 2π/3 to d 0.05 on 201 output points: after its first slip
/// the side, sliding on from the start, had a halt flagged at its rate's noise in a step whose
/// search found no sign change (f = 4.9e-9 at both ends of [7.5e-4, 7.5006e-4]), and the drag
/// ended as a solver failure. The step is now taken again, as long, with that contact sliding on
/// at a rate of zero (march.rs `after_step`, as `Flow::Quiet`), and the drag reaches d_max, every
/// row checked. (Its train of 224 slips differs from the 262 that 11 output points, or the
/// same scene to d 0.3, have up to d 0.05: the pair's slips follow the noise.)
#[test]
fn a_halt_at_the_noise_that_no_search_locates_is_not_a_failure() {
    let c = fine_uniform(2.0 * std::f64::consts::PI / 3.0, 0.05);
    let (out, r) = run_checked(&c, scene(&c), 201, HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    let r = r.expect("a start");
    assert_eq!(r.stop, StopReason::DMax, "{out}");
    assert!(r.slips.len() > 100, "{out}");
}

/// Was open (the property's seed 31 at 64 cases, found 2026-12-02; the same at d589eb2): a round
/// tip (r 0.0046) on the uniform rod over 0.00716/0.05 (flanks of 42°). The tip slips at
/// d 0.0114527 beside a side at s 0.910 that holds at its limit and a side at s 0.860 that slides
/// towards −x along with the stick before. 2.5e-7 into the slide the first side reaches its
/// limit and slips with the tip; in that state the other side moves towards +x at 0.79 of the
/// tip's rate against its friction, halts at the state's first point and, held no way on,
/// reversed there: its friction flipped by 2 μk N = 0.32 at once, and the state after the switch
/// had 9.66e-8 more elastic energy than the one before. No work was metered at the switch, so the
/// slip's dissipation exceeded its released energy by 9.66e-8 on 11, 21 and 201 output points
/// alike (the property asks 1e-8). A change at once that gains energy is no passive transition:
/// the slip now ends there as a jam (march.rs `reversal_jumps`), its rows checked, after the 151
/// slips before it.
#[test]
fn a_reversal_at_once_that_would_gain_energy_is_a_jam() {
    let c = Case {
        amp: 0.0071619724391352915,
        wave: 0.05,
        phase: 2.295963549537916,
        eta: 0.465525478202161,
        mu_s: 0.4203506351516142,
        ratio: 0.3183126315589918,
        taper: None,
        radius: 0.004616735552077759,
        d_max: 0.03,
    };
    let (out, r) = run_checked(&c, scene(&c), 11, HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    let r = r.expect("a start");
    assert_eq!(r.slips.len(), 151, "{out}");
    let StopReason::Jam { d, message } = &r.stop else {
        panic!("{out}");
    };
    assert!((d - 0.0114527).abs() < 1e-6, "{out}");
    assert!(message.contains("more elastic energy"), "{out}");
}

/// The property's seed 39 at 64 cases (found 2026-12-02): the row of a side's release at
/// d 0.0133039 had that side at N = −4.3e-18, its located root a rounding below zero. The contact
/// letting go has N = 0 there (march.rs `on_event`, as `at_zero`), and every row is checked.
#[test]
fn a_release_row_has_its_contact_at_zero_not_below() {
    open(&Case {
        amp: 0.007528453805103777,
        wave: 0.05255852259334255,
        phase: 3.1414078660059817,
        eta: 0.5565562168487712,
        mu_s: 0.6404117478425113,
        ratio: 0.6787866289862888,
        taper: Some(0.5634813275408215),
        radius: 0.0,
        d_max: 0.05100675073132795,
    });
}

/// Was open (the property's seed 44 at 64 cases): a round tip (r 0.002) on the uniform rod over
/// 0.00716/0.05. Slip 94 (d 0.0227379) slides a side 1.8e-3 along the surface; 2.4e-7 before
/// its end the tip touches down, and in that state the side's `|T| − μk N` falls by 2.8 over
/// the last 2.4e-7. Its end, located in `λ` to about 1.5e-15 there, leaves the side's `T` 1.8e-8 off
/// `μk N`: the precision of the located point at that rate, which the allowance now takes from
/// the slip's last contact state (`LOCATE`), not from the slip's mean rate (2.4e3).
#[test]
fn a_slider_at_a_slips_end_is_at_kinetic_friction() {
    open(&Case {
        amp: 0.0071619724391352915,
        wave: 0.05,
        phase: 0.0,
        eta: 0.5602371260941064,
        mu_s: 0.7956697537950501,
        ratio: 0.2,
        taper: None,
        radius: 0.002,
        d_max: 0.03,
    });
}

/// Was a solver failure (the property's seed 44 at 64 cases, shrunk): a round tip (r 0.00545)
/// on the uniform rod over 0.00716/0.05. The tip drives slip 65 (d 0.0220969) and lets go with
/// T = 0.075 still on it; held without it, the side beside it needs 0.0825 beyond μs N, and the
/// stick after the slip began with that side past its slip limit ("locating the Slip(0) event:
/// no sign change", f = 0.0825 at both ends). Driven on by that side, the slip's released energy
/// exceeds its friction work by 3.7e-7: the jump at the release. The release is a jam now
/// (`march.rs` `crossing_after_release`), the 64 slips before it checked.
#[test]
fn a_driver_that_lets_go_of_more_than_the_held_contacts_take_up_jams() {
    seed44_jams(0.2, 0.0220969, &["lets go", "(it would slip)"], 64);
}

/// The drag of the property's seed-44 scene (a round tip, r 0.00545, on the uniform rod over
/// 0.00716/0.05, η 0.560, μs 0.796) at μk/μs `ratio`, on 11 points: it ends as a jam at `d`
/// (to 1e-7) after `slips` slips, the jam's words holding each of `words`.
fn seed44_jams(ratio: f64, d: f64, words: &[&str], slips: usize) {
    let c = Case {
        amp: 0.0071619724391352915,
        wave: 0.05,
        phase: 0.0,
        eta: 0.5602371260941064,
        mu_s: 0.7956697537950501,
        ratio,
        taper: None,
        radius: 0.005452549590510744,
        d_max: 0.03,
    };
    let (out, r) = run_checked(&c, scene(&c), 11, HANG).unwrap();
    let r = r.unwrap();
    let StopReason::Jam { d: at, message } = &r.stop else {
        panic!("{out}");
    };
    assert!((at - d).abs() < 1e-7, "{out}");
    assert!(words.iter().all(|w| message.contains(w)), "{out}");
    assert_eq!(r.slips.len(), slips, "{out}");
}

/// The same scene with μk/μs 0.557 (the property's seed 44 at 64 cases, shrunk): the tip drives
/// slip 130 (d 0.0199858) 9.8e-8 along the surface and lets go with T = 0.040 on it; the side
/// beside it takes that force up within its static friction, but the jump to the state without
/// the tip released 1.0e-7 of elastic energy at once, and the slip's friction work fell short of
/// its released energy (1.2e-7) by as much. The release is a jam (`march.rs` `release_jump`),
/// the 130 slips before it balanced.
#[test]
fn a_driver_whose_release_jumps_beyond_the_balance_jams() {
    seed44_jams(
        0.5571847221522366,
        0.0199858,
        &["less elastic energy at once"],
        130,
    );
}

/// Was open (the property's seed 62 at 256 cases, found 2026-12-02; the same on the build before
/// that day's changes): the uniform rod, point tip, over 0.0175 sin(2πx/0.493 + 5.44) at η
/// 0.543, μs 0.783, μk/μs 0.687. A side 0.22 behind the tip slides passively towards −x in the
/// sticks; when the tip slips it must move with it, so it halts at the slip's first point, and
/// its held state's tangent (beyond 1e6) had it reversed at once (march.rs `reversed`). That jump
/// moved it 5.2e-5 the way it slid before, against its new friction, and released 1.8e-8 of
/// elastic energy that no contact's friction works off: slips 888 and 891 (d 0.0381940 and
/// 0.0504620) balanced only to 1.07e-8 and 1.79e-8 (the property asks 1e-8). Such a reversal
/// now takes the held state instead where its tangent is within 1e9 (march.rs `held_instead`):
/// the drag reaches d_max through the same 897 slips, each balanced.
#[test]
fn a_reversal_at_once_releases_no_unmetered_energy() {
    let c = Case {
        amp: 0.01749112126510604,
        wave: 0.49338453682538824,
        phase: 5.438846981772012,
        eta: 0.5426324955200333,
        mu_s: 0.7831432919454089,
        ratio: 0.6871434034742142,
        taper: None,
        radius: 0.0,
        d_max: 0.09746069206584196,
    };
    let (out, r) = run_checked(&c, scene(&c), 11, HANG).unwrap_or_else(|e| panic!("{c:?}: {e}"));
    let r = r.unwrap();
    assert_eq!(r.stop, StopReason::DMax, "{out}");
    assert_eq!(r.slips.len(), 897, "{out}");
}

/// Was open (the property's seed 67 at 256 cases): a round tip (r 0.0080) on the uniform rod
/// over 0.00395 sin(2πx/0.0657 + 1.65) at η 0.469, μs 0.3, μk 0.06. A side touches down at
/// s 0.899 (d 0.0363244) sliding towards −x beside a sliding side and the stuck tip, and halts
/// at the new state's first point; the halt's row had it at N = −2.2e-9, the noise of its
/// touchdown (5e-10 of the total 3.86), where the property asks N ≥ 0. That row now has it at
/// zero (march.rs, `at_noise`), as a lift-off's row has its contact.
#[test]
fn a_side_halting_as_it_lets_go_is_not_tensile() {
    open(&Case {
        amp: 0.003946795013025088,
        wave: 0.06565230787163912,
        phase: 1.6510424458576956,
        eta: 0.4686325581906174,
        mu_s: 0.3,
        ratio: 0.2,
        taper: None,
        radius: 0.008017267219306137,
        d_max: 0.08919330242952692,
    });
}

/// Was open (the property's seed 68 at 256 cases): the uniform rod, point tip, over
/// 0.00771 sin(2πx/0.123 + 2.81) at η 0.468, μs 0.329, μk/μs 0.498. At the end of slip 2979
/// (d 0.0125545) a side at s 0.8818 was recorded sliding towards +x with the friction
/// coefficient 0.0097 where μk is 0.1638: it broke free at a slip limit located on a jump of
/// the slide's branch, and slid with the ratio of the point before the jump. It now slides at
/// μs (`ContactForce::breaking_ratio`), relaxing to μk as the slip's driver.
#[test]
fn a_slider_at_a_slips_end_has_the_kinetic_coefficient() {
    open(&Case {
        amp: 0.00770859382429147,
        wave: 0.1225827535485442,
        phase: 2.8101434716434457,
        eta: 0.46804839016406086,
        mu_s: 0.32877714857144263,
        ratio: 0.4982531801819457,
        taper: None,
        radius: 0.0,
        d_max: 0.03,
    });
}

/// Was open (the property's seed 69 at 256 cases, the same at 354eb71): the rod tapered to
/// 0.601, point tip, over 0.00493 sin(2πx/0.235 + 2.30) at η 0.666, μs 0.551, μk/μs 0.608.
/// Slip 1859 (d 0.0793589): the tip slips beside a side 0.056 from it, the pair nearly
/// indeterminate; the side's `T` goes from −0.203 to +0.067 at the slide's first point and
/// beyond `μs N` 8.3e-10 later (`|T| − μs N` from −0.134 to +270 over the step), where its slip
/// limit was located, on the jump. It slid along with the ratio there, 0.1848, below μk 0.3350,
/// and ended the slip so. It now breaks free at μs; the tip, which kinetic friction then holds
/// from the new state's first point, ends its slide there (march.rs, `check_pending`), and the
/// side drives the slip on to where both slide at μk.
#[test]
fn a_tapered_slider_at_a_slips_end_has_the_kinetic_coefficient() {
    open(&Case {
        amp: 0.004929476943663062,
        wave: 0.23461859708650698,
        phase: 2.298416659754238,
        eta: 0.6662451610132596,
        mu_s: 0.5511803891970625,
        ratio: 0.6078425821525517,
        taper: Some(0.6012893411886773),
        radius: 0.0,
        d_max: 0.0858822517504988,
    });
}
