-- Roles of a DriftLab central store (docs/storage.md, "Roles" and "Ownership and verification").
-- Run once as the database's owner after the schema exists (the first DriftLab command on the
-- store creates it, with the server's own ownership rules, e.g.
-- driftlab-cli list --db postgresql://OWNER@HOST/DATABASE), then give each account a role:
--   CREATE ROLE rig3 LOGIN IN ROLE driftlab_rig;        -- a rig PC (password: ~/.pgpass there)
--   CREATE ROLE anna LOGIN IN ROLE driftlab_reviewer;   -- an engineer's desk
-- The grants below say which tables an account may touch; the server's triggers (installed by
-- DriftLab with the schema, CentralSchema) say which rows: a rig account adds its own sessions
-- and writes rows only into its own session while it is open; it marks it complete once, and
-- only with the digest the server computes from the stored rows; after that the session is
-- immutable for every rig account, its own included. Reviewers read and add their fits and
-- analyses to finished sessions. Only the owner deletes, renames or edits notes.
CREATE ROLE driftlab_rig NOLOGIN;
CREATE ROLE driftlab_reviewer NOLOGIN;
REVOKE CREATE ON SCHEMA public FROM PUBLIC;
GRANT SELECT ON ALL TABLES IN SCHEMA public TO driftlab_rig, driftlab_reviewer;
GRANT INSERT ON sessions, channels, sample_blocks, sample_levels, ir_frames, interferometer_points, events,
    fitted_models, analysis_results TO driftlab_rig;
-- A push adds its session open and marks it complete with the digest it claims.
GRANT UPDATE (complete, verified_sha256) ON sessions TO driftlab_rig;
-- A channel's min/max rows are rewritten while its samples are copied in (same transaction).
GRANT UPDATE ON sample_levels TO driftlab_rig;
GRANT INSERT ON fitted_models, analysis_results TO driftlab_reviewer;
GRANT USAGE ON ALL SEQUENCES IN SCHEMA public TO driftlab_rig, driftlab_reviewer;
