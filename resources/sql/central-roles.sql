-- Roles of a DriftLab central store (docs/storage.md, "Roles"). Run once as the database's
-- owner after the schema exists (the first DriftLab command on the store creates it, e.g.
-- driftlab-cli list --db postgresql://OWNER@HOST/DATABASE), then give each account a role:
--   CREATE ROLE rig3 LOGIN IN ROLE driftlab_rig;        -- a rig PC (password: ~/.pgpass there)
--   CREATE ROLE anna LOGIN IN ROLE driftlab_reviewer;   -- an engineer's desk
-- Rig accounts add sessions and read; they cannot delete or change a session (their own or
-- others'). Reviewers read and store their fits and analyses with a session. Only the owner
-- deletes, renames or edits notes.
CREATE ROLE driftlab_rig NOLOGIN;
CREATE ROLE driftlab_reviewer NOLOGIN;
GRANT SELECT ON ALL TABLES IN SCHEMA public TO driftlab_rig, driftlab_reviewer;
GRANT INSERT ON sessions, channels, sample_blocks, sample_levels, ir_frames, interferometer_points, events,
    fitted_models, analysis_results TO driftlab_rig;
-- A channel's min/max rows are rewritten while its samples are copied in (same transaction).
GRANT UPDATE ON sample_levels TO driftlab_rig;
GRANT INSERT ON fitted_models, analysis_results TO driftlab_reviewer;
GRANT USAGE ON ALL SEQUENCES IN SCHEMA public TO driftlab_rig, driftlab_reviewer;
