// Mass properties of a solid of uniform density bounded by a closed triangle mesh, exactly (up
// to rounding): the polyhedral volume integrals of Mirtich (1996, "Fast and Accurate
// Computation of Polyhedral Mass Properties", J. Graphics Tools 1(2)) as streamlined for
// triangles by Eberly ("Polyhedral Mass Properties (Revisited)", Geometric Tools, 2002); seed
// /work/shared/seeds/002_*, "Mirtich-Eberly Algorithm".
//
// The mesh must bound a solid: closed (every edge shared by exactly two triangles that run
// along it in opposite directions), triangles counter-clockwise seen from outside, none
// degenerate, positive enclosed volume, spanning 1e-60 m to 1e60 m (the integrals are of
// order span⁵). Vertices not used by any triangle are ignored.
//
// A mesh may consist of several pieces (separate closed surfaces). Each must be wound
// counter-clockwise seen from outside the solid: an outer surface has positive signed volume,
// the surface of a cavity, seen from inside the cavity, negative. An inside-out piece that
// does not lie inside another piece is refused (it would be negative mass), and so is any mesh
// whose tensor no solid can have. The integrals weight every point by how many pieces enclose
// it, so where solid pieces overlap their densities add up (the overlap counts twice), as if
// the pieces were separate bodies glued together; this is not checked.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/math.hpp"

namespace rigidlab {

// Vertex indices of a triangle, counting from 0 (messages count from 1, as Lua users do).
using MeshTriangle = std::array<int, 3>;

struct MeshMassProperties {
  double mass = 0.0;            // kg (density · volume)
  Vec3 com = Vec3::Zero();      // m
  Mat3 inertia = Mat3::Zero();  // kg·m², about com, axes of the mesh's frame
  double volume = 0.0;          // m³
};

// Empty when the mesh bounds a solid, otherwise one sentence saying what is wrong and where,
// with vertex and triangle numbers counting from 1: too few vertices or triangles, a
// non-finite vertex, an index out of range, a mesh too large or too small, a degenerate
// triangle, an open edge, an edge shared by more than two triangles, inconsistent winding, an
// inside-out mesh or piece, zero volume, a tensor no solid has.
std::string mesh_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles);

// Mass, COM, tensor about the COM and volume of the solid of `density` (kg/m³, finite, > 0)
// bounded by the mesh (vertices in m). Throws std::invalid_argument with mesh_problem's message
// for a mesh that does not bound a solid.
MeshMassProperties inertia_mesh(const std::vector<Vec3>& vertices,
                                const std::vector<MeshTriangle>& triangles,
                                double density = 1.0);

}  // namespace rigidlab
