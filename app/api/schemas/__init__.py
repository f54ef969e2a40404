"""Request and response models of the JSON API, one module per resource.

Response models describe the JSON the routes already produced, key for key
and in the same order: routes set ``response_model_exclude_unset=True`` so an
optional key (a parameter's ``step``, a quantity's ``text``) is written only
when the physics put it there, and numbers that may be integers are typed
:data:`~app.api.schemas.parameters.Number` so ``1`` is never rewritten ``1.0``.
"""
