//! The integration tests, one binary (rapier links once), one module per purpose.
//! Shared helpers live in `common`.

mod bad_input;
mod cli;
mod common;
mod energy_rpepo;
mod fe_pepo;
mod fe_rpepo;
mod footprint;
mod gate_check;
mod golden;
mod guarded_run;
mod mcap_cli;
mod mcap_traces;
mod paper_values;
mod predictor_corrector;
mod properties;
mod rapier_options;
mod rapier_pepo;
mod rapier_records;
mod rapier_rigid_block;
mod rapier_rpepo;
mod records_formats;
mod records_input;
mod records_newmark;
mod records_study;
mod references;
mod references_records;
mod references_rigid;
mod report_outputs;
mod report_sections;
mod robustness;
mod stability_classify;
mod sweep_energy;
mod sweep_order;
