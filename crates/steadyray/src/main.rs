//! The `steadyray` command: bench, render, scenes, adapters.

mod backend;
mod bench;
mod cli;
mod commands;
mod image_out;
mod view;

use clap::Parser;
use cli::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Bench(args) => bench::run(args),
        Command::Render(args) => commands::render::run(args),
        Command::Scenes => {
            commands::scenes::run();
            Ok(())
        }
        Command::Adapters => backend::print_adapters(),
        Command::Compare(args) => commands::compare::run(args),
        Command::Calibrate(args) => commands::calibrate::run(args),
        Command::View(args) => view::run(args),
        Command::Raybench(args) => commands::raybench::run(args),
        Command::Jod(args) => commands::jod::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
