"""Tied contacts as kinematic constraints (*CONTACT_TIED_..._TO_SURFACE).

Everything of ties at run time lives in this package: :mod:`.build` (set-up:
which node is tied where), :mod:`.search` (the closest master segment),
:mod:`.frame` (the tie frame of kept offsets), :mod:`.tieset` (the tie set
and the kernels of a cycle) and :mod:`.links` (what the penalty contacts
need to know of ties). The point of a segment closest to a node is the
projection shared with the penalty contact,
:func:`hollowbody.contact.geometry.closest_point`. A tie is a constraint,
but it is defined by a contact card, its sides are contact surfaces
(:mod:`hollowbody.contact.surface`) and the contacts' junction exclusions
depend on it: hence a subpackage of :mod:`hollowbody.contact`.

As LS-DYNA's constraint-based tied contacts: every slave node is bound to a
point of its closest master segment and follows it exactly; no penalty
spring, no time-step limit, linear momentum conserved.

**Set-up** (:func:`build_ties`, once, before masses and elements; the
Model is not changed):

1. Slave nodes: the node set (SSTYP 4) or the nodes of the slave segments /
   parts; master segments: the segment set (matched to the model's shells and
   solid faces) or the shells and exterior solid faces of the parts.
2. Each slave node is projected onto its closest master segment (natural
   coordinates u, v, see :mod:`hollowbody.contact.geometry`). It is tied
   when its distance ``d`` to that segment is within the search tolerance::

       tol = max(0.6 (t_s + t_m), 0.05 d_min)

   with ``t_s`` the slave node's shell thickness (SST when > 0) times SFST,
   ``t_m`` the segment's shell thickness (MST when > 0; 0 for solid faces)
   times SFMT, and ``d_min`` the segment's shorter diagonal (shortest edge of
   a triangle). A negative SST or MST sets the tolerance itself (the larger
   |value|). This is our rule, modelled on LS-DYNA's (thickness-based for
   shells, a fraction of the segment size for solids).
3. Without ``_OFFSET`` and with TIEDPRJ = 0 (*CONTROL_CONTACT, the default)
   the tied slave nodes are **moved onto the surface**, as LS-DYNA does: the
   tie set's ``node_x0`` holds the initial coordinates with the projected
   slaves (the run's reference configuration; the model keeps the deck's);
   with ``_OFFSET``, ``_CONSTRAINED_OFFSET`` or TIEDPRJ = 1 they stay where
   they are and their offset, stored in the segment's frame (e1, e2, n),
   follows the segment.
4. Not tied, and listed once in the run's messages with a count: nodes
   farther than the tolerance; nodes of rigid bodies, with an SPC on a
   translation, or with a prescribed motion (a constraint would fight the
   tie); nodes that are nodes of the master surface (already joined by the
   mesh); nodes already tied by an earlier tie. A slave node that is a node of
   a segment another tie uses (a chain) is an error.

**Masses** (:meth:`TieSet.transfer_mass`): each slave's mass is added to
its segment's nodes with the shape-function weights N_j and the slave keeps
none (likewise rotational inertia where rotations are coupled). The
effective masses m'_j = m_j + sum_s N_j(s) m_s make the constraint
momentum-exact: the momentum sum_i m_i v_i of the true masses equals
sum_j m'_j v_j.

**Every cycle** (numba kernels over the tie arrays, nothing allocated):

- :meth:`TieSet.distribute` (after element and contact forces): f_j += N_j
  f_s, f_s = 0 (and the moments of rotation-coupled slaves);
- the masters' accelerations follow from f / m' as for every node;
- :meth:`TieSet.follow` (after the positions are updated and constraints
  imposed): x_s = sum N_j x_j + R d_loc, v_s = sum N_j v_j + (R^{n+1} -
  R^n) d_loc / dt (R: the segment frame, d_loc the stored offset; 0 when
  projected), and for rotation-coupled slaves w_s = sum N_j w_j.

**Rotations.** *CONTACT_TIED_SHELL_EDGE_TO_SURFACE couples the rotational
velocity of a slave that is a shell node (6 DOFs) to the interpolated
rotational velocity of its segment's nodes when these have rotational DOFs
(shell masters or rigid-body nodes): the shell edge is clamped to the
surface, as a shared node would be. On solid faces (no rotational DOFs) only
translations are tied and the shell edge is a hinge along the surface.
NODES_TO_SURFACE and SURFACE_TO_SURFACE tie translations only (the slave's
rotations, if any, stay free). SURFACE_TO_SURFACE ties the slave surface's
nodes to the master surface (one way, like NODES_TO_SURFACE).

**Limits.** With an offset, forces are distributed with the shape functions
only (the moment of the force about the offset arm is not passed on); exact
for projected nodes. A rigid master part with *PART_INERTIA keeps its given
mass (the slave mass moved to its nodes is lost).
"""

from hollowbody.contact.tied.build import build_ties
from hollowbody.contact.tied.links import tie_links, tied_links
from hollowbody.contact.tied.tieset import TieSet

__all__ = ["TieSet", "build_ties", "tie_links", "tied_links"]
