// SPDX-License-Identifier: MIT
// The modules' small defs (granflow/defs.h, issue 24): built once from a
// config, the only code outside the parser that reads gf_config's fields;
// and the typed setters of the code that edits a config.
#include "granflow/defs.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "config/derive.h"

double gf_config_r_e(const gf_config *cfg)
{
    return isnan(cfg->relax_radius) ? cfg->spot_radius + 1.0 : cfg->relax_radius;
}

double gf_config_insertion_margin(const gf_config *cfg)
{
    return isnan(cfg->spot_insertion_margin) ? cfg->spot_radius : cfg->spot_insertion_margin;
}

double gf_config_dem_kt(const gf_config *cfg) { return isnan(cfg->dem_kt) ? 2.0 / 7.0 * cfg->dem_kn : cfg->dem_kt; }

double gf_config_dem_gammat(const gf_config *cfg)
{
    return isnan(cfg->dem_gammat) ? 0.5 * cfg->dem_gamman : cfg->dem_gammat;
}

int gf_config_threads(const gf_config *cfg)
{
    return cfg->run_threads > 0 ? (int)cfg->run_threads : gf_cpu_count();
}

double gf_config_exit_plane(const gf_config *cfg)
{
    // A cylinder's pipe and a wedge's chute: particles leave at their end.
    return cfg->container_shape == GF_SHAPE_BOX ? cfg->exit_z : cfg->exit_z - cfg->outlet_length;
}

void gf_config_container_defs(const gf_config *cfg, gf_container_defs *d)
{
    memset(d, 0, sizeof *d);
    d->shape = cfg->container_shape;
    d->width = cfg->container_width;
    d->depth = cfg->container_depth;
    d->orifice.shape = cfg->orifice_shape;
    d->orifice.diameter = cfg->orifice_diameter;
    d->orifice.x = cfg->orifice_x;
    d->orifice.y = cfg->orifice_y;
    d->exit_level = cfg->exit_z;
    d->exit_plane = gf_config_exit_plane(cfg);
    d->radius = cfg->container_radius;
    d->angle = cfg->hopper_angle;
    d->outlet.diameter = cfg->outlet_diameter;
    d->outlet.length = cfg->outlet_length;
    d->column_radius = cfg->inner_radius;
    memcpy(d->mesh, cfg->container_mesh, sizeof d->mesh);
    d->mesh_scale = cfg->container_mesh_scale;
    d->mesh_resolution = cfg->container_mesh_resolution;
}

void gf_config_engine_defs(const gf_config *cfg, gf_engine_defs *d)
{
    memset(d, 0, sizeof *d);
    gf_spot_params sp; // the spot's own parameters, from their one builder
    gf_config_spot_params(cfg, &sp);
    d->radius = sp.radius;
    d->w = sp.w;
    d->insertion_rate = sp.insertion_rate;
    d->move_rate = sp.move_rate;
    d->step_xy = sp.step_xy;
    d->step_z = sp.step_z;
    d->wall_distance = sp.wall_distance;
    d->insertion_margin = sp.insertion_margin;
    d->ball_centre = cfg->spot_ball_centre;
    d->insertion_radius = fmax(0.0, 0.5 * cfg->orifice_diameter - d->insertion_margin);
    // SPEC 1.3 mass balance: a spot is born one radius below the exit, so its
    // ball sweeps its whole volume past the exit plane as it rises.
    d->birth_z = gf_config_exit_plane(cfg) - cfg->spot_radius;
    d->bias_exponent = cfg->spot_bias_exponent;
    d->weighting = cfg->spot_weighting != 0;
    d->weighting_min_count = cfg->spot_weighting_min_count;
    d->weighting_zmin = cfg->spot_weighting_zmin;
    d->weighting_bulk_count = cfg->spot_weighting_bulk_count;
    d->walls = cfg->spot_walls;
    d->flow_rule = cfg->spot_flow_rule;
    d->sfr_rise = cfg->spot_sfr_rise;
    d->alpha = cfg->relax_alpha;
    d->r_e = sp.r_e;
    d->method = cfg->relax_method;
    d->k = cfg->relax_k;
    d->duration = cfg->run_duration;
    d->seed = cfg->run_seed;
    d->checkpoint_interval = cfg->run_checkpoint_interval;
    d->stall_time = cfg->run_stall_time;
    d->reorder_interval = cfg->run_reorder_interval;
    d->mode = cfg->run_mode;
    d->order = cfg->run_order;
    d->threads = gf_config_threads(cfg);
    d->threads_auto = cfg->run_threads <= 0;
    d->spatial = cfg->run_mode == GF_MODE_FIXED &&
                 (cfg->run_order == GF_ORDER_SPATIAL || cfg->run_order == GF_ORDER_DOMAINS ||
                  cfg->run_order == GF_ORDER_SWEEP);
    d->recirculate = cfg->run_recirculate != 0;
    d->max_passes = cfg->run_max_passes;
    d->reinsert = cfg->run_reinsert;
    d->reinsert_rmin = cfg->run_reinsert_rmin;
    d->reinsert_rmax = cfg->run_reinsert_rmax;
    d->window = cfg->parallel_window;
    d->domain_size = cfg->parallel_domain_size;
    d->sectors = cfg->parallel_sectors;
    d->cut = cfg->parallel_cut;
    d->sweeps = cfg->parallel_sweeps;
    d->snapshot_interval = cfg->output_snapshot_interval;
}

void gf_config_packing_defs(const gf_config *cfg, gf_packing_defs *d)
{
    memset(d, 0, sizeof *d);
    d->particles = cfg->packing_particles;
    d->fill_height = cfg->packing_fill_height;
    memcpy(d->file, cfg->packing_file, sizeof d->file);
    d->layer_thickness = cfg->packing_layer_thickness;
    memcpy(d->types, cfg->packing_types, sizeof d->types);
    d->radius2 = cfg->packing_radius2;
    d->fraction2 = cfg->packing_fraction2;
    d->unit_diameter = cfg->dump_diameter;
    d->unit_gravity = cfg->dump_gravity;
    d->seed = cfg->run_seed;
}

void gf_config_rundir_defs(const gf_config *cfg, gf_rundir_defs *d)
{
    memset(d, 0, sizeof *d);
    d->duration = cfg->run_duration;
    d->stall_time = cfg->run_stall_time;
    d->snapshot_interval = cfg->output_snapshot_interval;
    d->seed = cfg->run_seed;
    d->recirculate = cfg->run_recirculate != 0;
    d->format = cfg->output_format;
    d->vtk_encoding = cfg->output_vtk_encoding;
    memcpy(d->packing, cfg->packing_file, sizeof d->packing);
    d->unit_diameter = cfg->dump_diameter;
    d->exit_level = cfg->exit_z;
}

void gf_config_dem_defs(const gf_config *cfg, gf_dem_defs *d)
{
    memset(d, 0, sizeof *d);
    d->friction = cfg->dem_friction;
    d->kn = cfg->dem_kn;
    d->kt = gf_config_dem_kt(cfg);
    d->gamman = cfg->dem_gamman;
    d->gammat = gf_config_dem_gammat(cfg);
    d->timestep = cfg->dem_timestep;
    d->fill = cfg->dem_fill_method;
    d->settle_time = cfg->dem_settle_time;
    d->settle_ke = cfg->dem_settle_ke;
    d->mpi_ranks = cfg->dem_mpi_ranks;
    d->restart_interval = cfg->dem_restart_interval;
    d->duration = cfg->run_duration;
    d->snapshot_interval = cfg->output_snapshot_interval;
    d->particles = cfg->packing_particles;
    d->fill_height = cfg->packing_fill_height;
    d->seed = cfg->run_seed;
}

void gf_config_lga_defs(const gf_config *cfg, gf_lga_defs *d)
{
    memset(d, 0, sizeof *d);
    d->scenario = cfg->lga_scenario;
    d->flow = cfg->lga_silo_flow;
    d->p = cfg->lga_p;
    d->q = cfg->lga_q;
    d->g = cfg->lga_g;
    d->h = cfg->lga_h;
    d->k = cfg->lga_k;
    d->b = cfg->lga_b;
    d->iterations = cfg->lga_iterations;
    d->width = cfg->lga_width;
    d->height = cfg->lga_height;
    d->particles = cfg->lga_particles;
    d->feed_rate = cfg->lga_feed_rate;
    d->angle = cfg->lga_hopper_angle;
    d->outlet_width = cfg->lga_outlet_width;
    d->snapshot_interval = cfg->lga_snapshot_interval;
    d->seed = cfg->run_seed;
}

void gf_config_spot_params(const gf_config *cfg, gf_spot_params *d)
{
    memset(d, 0, sizeof *d);
    d->radius = cfg->spot_radius;
    d->w = cfg->spot_w;
    d->insertion_rate = cfg->spot_insertion_rate;
    d->move_rate = cfg->spot_move_rate;
    d->step_xy = cfg->spot_step_xy;
    d->step_z = cfg->spot_step_z;
    d->wall_distance = cfg->spot_wall_distance;
    d->insertion_margin = gf_config_insertion_margin(cfg);
    d->r_e = gf_config_r_e(cfg);
}

void gf_config_set_spot_fit(gf_config *cfg, double radius, double w, double insertion_rate, double move_rate,
                            double step_xy)
{
    cfg->spot_radius = radius;
    cfg->spot_w = w;
    cfg->spot_insertion_rate = insertion_rate;
    cfg->spot_move_rate = move_rate;
    cfg->spot_step_xy = step_xy;
    cfg->spot_insertion_margin = NAN; // auto: follow the new radius
    cfg->relax_radius = NAN;
}

void gf_config_set_threads(gf_config *cfg, int64_t threads) { cfg->run_threads = threads > 0 ? threads : 0; }

void gf_config_set_extent(gf_config *cfg, double width, double depth)
{
    cfg->container_width = width;
    cfg->container_depth = depth;
}

void gf_config_set_orifice(gf_config *cfg, gf_orifice_shape shape, double diameter)
{
    cfg->orifice_shape = shape;
    cfg->orifice_diameter = diameter;
}

void gf_config_set_dump_units(gf_config *cfg, double diameter, double gravity)
{
    cfg->dump_diameter = diameter;
    cfg->dump_gravity = gravity;
}

void gf_config_set_mesh_path(gf_config *cfg, const char *path)
{
    snprintf(cfg->container_mesh, sizeof cfg->container_mesh, "%s", path);
}

void gf_config_reset_run_keys(gf_config *cfg)
{
    const gf_config d = gf_config_default();
    cfg->run_duration = d.run_duration;
    cfg->run_checkpoint_interval = d.run_checkpoint_interval;
    cfg->run_stall_time = d.run_stall_time;
    cfg->run_threads = d.run_threads; // results do not depend on it
}
