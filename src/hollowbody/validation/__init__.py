"""The paper's segment tests on a body model, rated against cadaver data.

``cases`` lists the tests (source, impactor, speeds, data), ``setup`` the
record a set-up returns, ``impact`` the lateral hub impacts on the full body
(pelvis, abdomen, thorax, shoulder), ``bending`` the limb three-point bending
cut from the body, ``landmarks`` the landmark file of a user's own model,
``signals`` reads a run's force, deflection and moment, ``ratings`` rates
them, ``report`` writes the plots and the Markdown/HTML report and ``runner``
runs a case end to end.
"""
