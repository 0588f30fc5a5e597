/* The numbers the C code and the GLSL shaders share: the values of the
 * variant switches (common.glsl lists the switches). This file is valid C
 * and valid GLSL, so it holds only comments and #define lines of integer
 * constants. gs_params.c includes it to write a variant's #define lines;
 * the program builder (gs_program.c) puts it into every shader after
 * "#version 450 core" and before the variant's #defines, so the shaders
 * compare the switches with these names rather than with literals. */
#ifndef GS_SHARED_H
#define GS_SHARED_H

/* LIGHT_TYPE: the kind of the light a program draws. */
#define GS_LIGHT_POINT 0
#define GS_LIGHT_SPOT 1
#define GS_LIGHT_DIRECTIONAL 2

/* PHASE: the medium's phase function (sh_phase_eval). */
#define GS_PHASE_ISOTROPIC 0
#define GS_PHASE_HENYEY_GREENSTEIN 1
#define GS_PHASE_NISHITA_HAZY 2
#define GS_PHASE_NISHITA_MURKY 3
#define GS_PHASE_RAYLEIGH 4
#define GS_PHASE_CORNETTE_SHANKS 5

/* MEDIUM: the medium's kind (sh_medium_type; gs_medium.h, medium.glsl). */
#define GS_MEDIUM_HOMOGENEOUS 0
#define GS_MEDIUM_HEIGHT_FOG 1
#define GS_MEDIUM_ATMOSPHERE 2

/* SHADOW: the light's shadow map (gs_lightvol.h). */
#define GS_SHADOW_NONE 0
#define GS_SHADOW_2D 1
#define GS_SHADOW_CUBE 2

/* SPOT_SMOOTH: the spot profile's edge; BY_VALUE chooses per fragment from
 * the cone's angles (live programs). */
#define GS_SPOT_HARD 0
#define GS_SPOT_SMOOTH 1
#define GS_SPOT_BY_VALUE 2

/* SPOT_EXPONENT: the class of the spot's cosine exponent. */
#define GS_SPOT_EXPONENT_0 0
#define GS_SPOT_EXPONENT_1 1
#define GS_SPOT_EXPONENT_ANY 2

/* The most sampling planes or spheres an atmosphere's frame draws (the
 * compose pass holds their depths or radii in a uniform array). */
#define GS_ATMO_MAX_LAYERS 64

/* Texture units: where the C code binds each texture the shaders sample
 * (layout(binding = ...)). Units from GS_UNIT_FREE up are unused by the
 * renderer (the tests use them). */
#define GS_UNIT_MAP 0         /* the light map, u_map */
#define GS_UNIT_SHADOW_2D 1   /* u_shadow2d */
#define GS_UNIT_SHADOW_CUBE 2 /* u_shadowcube */
#define GS_UNIT_INTERVAL 3    /* the sweep's ray intervals, u_interval */
#define GS_UNIT_XI 4          /* the xi lattice, u_xi */
#define GS_UNIT_LINDEPTH 5    /* the surfaces' view depth, u_lindepth */
#define GS_UNIT_ATMO 6        /* the atmosphere's optical depths, u_table */
#define GS_UNIT_ATMO_LATTICE 7 /* the sky's lattice, u_lattice */
/* The shadow map again, through a sampler that returns its stored depths
 * filtered (no comparison): u_shadow2d_depth, u_shadowcube_depth. */
#define GS_UNIT_SHADOW_DEPTH_2D 8
#define GS_UNIT_SHADOW_DEPTH_CUBE 9
#define GS_UNIT_FREE 10

#endif
