//! `vibrissa`: the command-line program of the vibrissa workspace (see README and `--help`).

mod chart;
mod cli;
mod drag;
mod dynamics;
mod error;
mod figures;
mod journal;
mod modes;
mod number_text;
mod output_files;
mod peg;
mod plot;
mod present;
mod progress;
mod scan;
mod scene_args;
mod solve;
mod sweep;
mod table;
mod texture;
mod validate;

use clap::error::ErrorKind;
use clap::FromArgMatches;
use cli::{Cli, Command};
use error::{one_line, Fail, Res};
use std::io::Write;

/// Turn a clap error into one line (`error: ...`, with a tip if clap has one).
fn clap_one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let mut parts = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with("Usage:") || t.starts_with("For more information") {
            break;
        }
        if !t.is_empty() {
            parts.push(t.replace("tip: ", "; tip: "));
        }
    }
    let msg = one_line(&parts.join(" "));
    let msg = msg.strip_prefix("error: ").unwrap_or(&msg).to_string();
    format!("{msg} (see --help)")
}

/// Exit for a clap outcome: help and version on stdout (exit 0, or 1 when stdout cannot be
/// written; a closed pipe is not an error), anything else one line on stderr with exit 2.
fn clap_exit(e: clap::Error) -> ! {
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let r = e.print().and_then(|_| std::io::stdout().flush());
            match r {
                Err(err) if err.kind() != std::io::ErrorKind::BrokenPipe => {
                    progress::eprint(&format!("error: writing the help text to stdout: {err}"));
                    std::process::exit(1)
                }
                _ => std::process::exit(0),
            }
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            std::process::exit(2)
        }
        _ => {
            progress::eprint(&format!("error: {}", clap_one_line(&e)));
            std::process::exit(2)
        }
    }
}

/// Everything that must hold before any work: values in range, the scene, the outputs (no two
/// the same, directories writable; temporaries created). `sweep` does its own, with the grid.
fn prepare(cmd: &mut Command) -> Res<()> {
    validate::command(cmd)?;
    match cmd {
        Command::Solve(a) => {
            scene_args::build_scene(&a.scene, None)?;
            if let Some(p) = &a.shape_out {
                output_files::plan(&[("--shape-out", p)], false)?;
            }
        }
        Command::Scan(a) => {
            scene_args::build_scene(&a.scene, a.eta)?;
            plan_table(&a.out, &a.shapes)?;
        }
        Command::Infer(a) => {
            scene_args::build_scene(&a.scene, a.eta)?;
        }
        Command::Plot(a) => {
            let out = plot::out_path(a);
            output_files::plan(&[("--out", out.as_path())], false)?;
        }
        Command::Whisk(a) => {
            scene_args::build_scene(&a.scene, None)?;
            plan_table(&a.out, &a.shapes)?;
        }
        Command::Locate(a) => {
            scene_args::build_scene(&a.scene, None)?;
        }
        Command::Drag(a) => {
            drag::foot_speed(a, &drag::scene(a)?)?;
            plan_table(&a.out, &a.shapes)?;
        }
        Command::Fit(a) => {
            scene_args::build_scene(&a.scene, a.eta)?;
        }
        Command::Modes(a) => {
            scene_args::build_scene(&a.scene, None)?;
        }
        Command::Dynamics(a) => match &a.command {
            cli::DynamicsCommand::Drag(d) => {
                scene_args::build_scene(&d.scene, d.eta)?;
                dynamics::options(d)?.validate()?;
                plan_spectrum(&d.spectrum)?;
            }
            cli::DynamicsCommand::Free(f) => {
                scene_args::build_scene(&f.scene, None)?;
                dynamics::free_options(f).validate()?;
                plan_spectrum(&f.spectrum)?;
            }
        },
        Command::Sweep(_) | Command::Figures(_) => {}
    }
    Ok(())
}

/// The `--spectrum` file of a `dynamics` command.
fn plan_spectrum(p: &Option<std::path::PathBuf>) -> Res<()> {
    match p {
        Some(p) => output_files::plan(&[("--spectrum", p.as_path())], false),
        None => Ok(()),
    }
}

/// The files of a command with `--out` and `--shapes` (see `output_files::plan`).
fn plan_table(out: &Option<std::path::PathBuf>, shapes: &Option<std::path::PathBuf>) -> Res<()> {
    let mut outs = Vec::new();
    if let Some(p) = out {
        outs.push(("--out", p.as_path()));
    }
    if let Some(p) = shapes {
        outs.push(("--shapes", p.as_path()));
    }
    output_files::plan(&outs, false)
}

fn run(mut cli: Cli) -> Res<()> {
    prepare(&mut cli.command)?;
    match &cli.command {
        Command::Solve(a) => {
            progress::start("solve", false);
            if a.peg.is_some() {
                peg::run_solve(a)
            } else {
                solve::run(a)
            }
        }
        Command::Scan(a) => {
            progress::start("scan", false);
            scan::run(a)
        }
        Command::Infer(a) => {
            progress::start("infer", false);
            scan::run_infer(a)
        }
        Command::Sweep(a) => sweep::run(a),
        Command::Whisk(a) => {
            progress::start("whisk", false);
            peg::run_whisk(a)
        }
        Command::Locate(a) => {
            progress::start("locate", false);
            peg::run_locate(a)
        }
        Command::Drag(a) => {
            progress::start("drag", false);
            drag::run(a)
        }
        Command::Fit(a) => {
            progress::start("fit", false);
            drag::run_fit(a)
        }
        Command::Figures(a) => {
            progress::start("figures", true);
            figures::run(a)
        }
        Command::Plot(a) => plot::run(a),
        Command::Modes(a) => {
            progress::start("modes", false);
            modes::run(a)
        }
        Command::Dynamics(a) => {
            progress::start("dynamics", false);
            dynamics::run(a)
        }
    }
}

fn main() {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    if let Some(msg) = cli::missing_value(&args) {
        progress::eprint(&format!("error: {msg} (see --help)"));
        std::process::exit(2);
    }
    let matches = cli::command()
        .try_get_matches_from(&args)
        .unwrap_or_else(|e| clap_exit(e));
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| clap_exit(e));
    // a panic would be a bug; still, report it as one line, not a backtrace, and leave no
    // temporary file behind
    std::panic::set_hook(Box::new(|info| {
        if sweep::QUIET_PANICS.load(std::sync::atomic::Ordering::SeqCst) {
            return;
        }
        output_files::abort_if_free();
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        progress::eprint(&format!("error: internal error: {}", one_line(&msg)));
    }));
    let r = run(cli);
    progress::stop();
    let r = match r {
        // the reader of stdout went away: the command's files are complete, keep them
        Ok(()) | Err(Fail::Closed) => output_files::commit_all(),
        Err(e) => {
            output_files::abort_all();
            Err(e)
        }
    };
    if let Err(e) = r.map_err(error::explain) {
        progress::note(&format!("error: {}", e.message()));
        std::process::exit(e.code());
    }
}
