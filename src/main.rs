//! `vibrissa`: the command-line program of the vibrissa workspace (see README and `--help`).

mod cli;
mod error;
mod figures;
mod numeric;
mod output;
mod scan;
mod scene_args;
mod solve;
mod sweep;

use clap::error::ErrorKind;
use clap::Parser;
use cli::{Cli, Command};
use error::{one_line, Fail};

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

fn run(cli: Cli) -> Result<(), Fail> {
    match cli.command {
        Command::Solve(a) => solve::run(&a),
        Command::Scan(a) => scan::run(&a),
        Command::Infer(a) => scan::run_infer(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Figures(a) => figures::run(&a),
    }
}

fn main() {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                let _ = e.print();
                std::process::exit(
                    if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                        2
                    } else {
                        0
                    },
                );
            }
            _ => {
                eprintln!("error: {}", clap_one_line(&e));
                std::process::exit(2);
            }
        },
    };
    // a panic would be a bug; still, report it as one line, not a backtrace
    std::panic::set_hook(Box::new(|info| {
        if sweep::QUIET_PANICS.load(std::sync::atomic::Ordering::SeqCst) {
            return;
        }
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        eprintln!("error: internal error: {}", one_line(&msg));
    }));
    match run(cli) {
        Ok(()) => {}
        Err(Fail::Closed) => {}
        Err(e) => {
            eprintln!("error: {}", e.message());
            std::process::exit(e.code());
        }
    }
}
