"""``fem_axi``: the axisymmetric continuum of rod and impactor with real (unilateral) contact.

What lives here: :mod:`.problem` (the geometry of both bodies and the scales), :mod:`.options`
(the settings), :mod:`.meshes` (the meshes of the bare rod, the ball and the cap in the (r, z)
half-plane), :mod:`.mesh_geometry` (the measures and operations on triangle meshes that both
meshers share: areas, longest edges, orientation, named boundaries, the graded target size and
the refinement loop), :mod:`.film_mesh` (the rod with a bonded film disc on its struck end),
:mod:`.layers` (how a film or stack is divided through its thickness, and the check of a positive
argument, without the mesher's imports), :mod:`.film_model` (the film's region and its contact
nodes), :mod:`.axisym` (the r-weighted elasticity forms), :mod:`.plasticity` (J2 plasticity's
return mapping and consistent tangent at a body's points), :mod:`.plastic_region` (the elements near
the contact where a yielding material may yield, their strain operator and response, and the
check that the elastic rest stays below yield), :mod:`.plastic_step` (a dynamic step with the
plastic regions: the plastic load iterated with the elastic factorisation), :mod:`.axibody` (one body's Newmark
operators), :mod:`.farbar` (the rod beyond a few diameters as a 1-D bar joined to the continuum),
:mod:`.gauges` (where the stations' and gauges' strain is read, and how far the continuum
must reach for the gauges),
:mod:`.contact` (the candidate gaps, G = K_eff^-1 B^T and the contact LCP), :mod:`.separation`
(the end test: the energy bound that no contact can follow), :mod:`.aximodel` (the model
assembled: both bodies and the contact's candidates), :mod:`.solver`
(:func:`~rodimpact.solvers.fem_axi.solver.solve_fem_axi`), :mod:`.cost` (its cost model) and
:mod:`.indentation` (the static indentation, elastic-plastic where a material yields).

What it may import: :mod:`rodimpact.contact` (for the scales and the film's description
only: the continuum resolves the contact, and the film, itself), :mod:`rodimpact.model`,
:mod:`rodimpact.analysis.signals`, the shared pieces of :mod:`rodimpact.solvers`, scikit-fem
and qdldl (the LDL^T factor). This ``__init__`` imports nothing.
"""
