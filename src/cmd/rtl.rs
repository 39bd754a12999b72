//! RTL commands: export-verilog, sim, synth (stub).

#[derive(clap::Args, Debug)]
pub struct ExportArgs {}
#[derive(clap::Args, Debug)]
pub struct SimArgs {}
#[derive(clap::Args, Debug)]
pub struct SynthArgs {}

pub fn export(_a: ExportArgs) -> anyhow::Result<()> {
    anyhow::bail!("not implemented yet")
}
pub fn sim(_a: SimArgs) -> anyhow::Result<()> {
    anyhow::bail!("not implemented yet")
}
pub fn synth(_a: SynthArgs) -> anyhow::Result<()> {
    anyhow::bail!("not implemented yet")
}
