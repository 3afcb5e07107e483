//! The `ssgi` command line: [`args`] says what was asked (clap), [`parse`] reads it (and
//! warns about options that change nothing), [`jobs`] does it. The binary only parses and
//! dispatches.

pub mod args;
pub mod jobs;
pub mod parse;
mod unused;

pub use args::{
    AccumulateMode, BenchArgs, Cli, Command, RenderArgs, SceneArgs, TableArgs, ViewArgs,
};
pub use jobs::{bench, reference, render, stress, sweep, table, view};
