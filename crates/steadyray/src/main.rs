//! The `steadyray` command: bench, render, scenes, adapters.

mod cli;
mod commands;
mod image_out;
mod view;

use clap::Parser;
use cli::{Cli, Command};
use std::process::ExitCode;
use steadyray_experiment::{backend, bench, calibrate, compare, jod, raybench, suite};

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Bench(args) => bench::run(&args.config()),
        Command::Render(args) => commands::render::run(args),
        Command::Scenes => {
            commands::scenes::run();
            Ok(())
        }
        Command::Adapters => backend::print_adapters(),
        Command::Controllers => {
            print!("{}", steadyray_control::options::describe_controllers());
            Ok(())
        }
        Command::Compare(args) => compare::run(&args.into()),
        Command::Calibrate(args) => calibrate::run(&args.into()),
        Command::View(args) => view::run(args),
        Command::Raybench(args) => raybench::run(&args.into()),
        Command::Jod(args) => jod::run(&args.into()),
        Command::Suite(args) => run_suite(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// `steadyray suite run` and `steadyray suite table`.
fn run_suite(args: &cli::suite::SuiteArgs) -> anyhow::Result<()> {
    match &args.command {
        cli::suite::SuiteCommand::Run(run) => suite::run(&run.config()?, &cli::suite::CommandLine),
        cli::suite::SuiteCommand::Table(table) => {
            let out = table
                .out
                .clone()
                .unwrap_or_else(|| table.folders[0].clone());
            print!("{}", suite::write_table(&table.folders, &out)?);
            eprintln!(
                "suite: wrote table.md, table.json, suite.png and suite.svg to {}",
                out.display()
            );
            Ok(())
        }
    }
}
