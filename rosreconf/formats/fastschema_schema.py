"""The verdict of interoperability-schema.schema.json as code: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = '813d848e930efe719d38e71b18f79ced22d1113629c40e7302916d34b649d83d'
import re

_NUMBER = (int, float)
_MISSING = object()
_C0 = frozenset({'edges', 'environment', 'format', 'name', 'nominal', 'roles', 'simulation', 'skill', 'title', 'version'})
_C1 = re.compile('^[A-Za-z][A-Za-z0-9_]*$').search
_C2 = set()  # texts _C1 matched
_C3 = frozenset({'abstraction', 'description', 'name', 'optional'})
_C4 = frozenset({'consumer', 'interfaces', 'optional', 'providers'})
_C5 = re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$').search
_C6 = set()  # texts _C5 matched
_C7 = frozenset({'duration', 'loops', 'reference', 'requirements'})
_C8 = frozenset({'feedback', 'forward', 'name', 'plant'})
_C9 = frozenset({'delay', 'state_space', 'transfer_function'})
_C10 = frozenset({'den', 'num'})
_C11 = frozenset({'A', 'B', 'C', 'D'})
_C12 = frozenset({'overshoot', 'settling_time', 'steady_state_error'})


def validate(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C0:
        return False
    v1 = data.get('format', _MISSING)
    if v1 is _MISSING:
        return False
    if not (type(v1) is str and v1 == 'rosreconf/interoperability-schema'):
        return False
    v2 = data.get('version', _MISSING)
    if v2 is _MISSING:
        return False
    if not (type(v2) in _NUMBER and v2 == 1):
        return False
    v3 = data.get('name', _MISSING)
    if v3 is _MISSING:
        return False
    if not type(v3) is str:
        return False
    if v3 not in _C2:
        if _C1(v3) is None:
            return False
        if len(_C2) < 100000:
            _C2.add(v3)
    v4 = data.get('title', _MISSING)
    if v4 is not _MISSING:
        if not type(v4) is str:
            return False
    v5 = data.get('skill', _MISSING)
    if v5 is _MISSING:
        return False
    if not type(v5) is str:
        return False
    v6 = data.get('environment', _MISSING)
    if v6 is _MISSING:
        return False
    if not type(v6) is str:
        return False
    v7 = data.get('roles', _MISSING)
    if v7 is _MISSING:
        return False
    if not type(v7) is list:
        return False
    if len(v7) < 1:
        return False
    for v8 in v7:
        if not type(v8) is dict:
            return False
        if not v8.keys() <= _C3:
            return False
        v9 = v8.get('name', _MISSING)
        if v9 is _MISSING:
            return False
        if not type(v9) is str:
            return False
        if v9 not in _C2:
            if _C1(v9) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v9)
        v10 = v8.get('abstraction', _MISSING)
        if v10 is _MISSING:
            return False
        if not type(v10) is str:
            return False
        if v10 not in _C2:
            if _C1(v10) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v10)
        v11 = v8.get('description', _MISSING)
        if v11 is not _MISSING:
            if not type(v11) is str:
                return False
        v12 = v8.get('optional', _MISSING)
        if v12 is not _MISSING:
            if not type(v12) is bool:
                return False
    v13 = data.get('edges', _MISSING)
    if v13 is not _MISSING:
        if not type(v13) is list:
            return False
        for v14 in v13:
            if not type(v14) is dict:
                return False
            if not v14.keys() <= _C4:
                return False
            v15 = v14.get('consumer', _MISSING)
            if v15 is _MISSING:
                return False
            if not type(v15) is str:
                return False
            if v15 not in _C2:
                if _C1(v15) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v15)
            v16 = v14.get('providers', _MISSING)
            if v16 is _MISSING:
                return False
            if not type(v16) is list:
                return False
            if len(v16) < 1:
                return False
            for v17 in v16:
                if not type(v17) is str:
                    return False
                if v17 not in _C2:
                    if _C1(v17) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v17)
            if len(set(v16)) != len(v16):
                return False
            v18 = v14.get('interfaces', _MISSING)
            if v18 is not _MISSING:
                if not type(v18) is list:
                    return False
                if len(v18) < 1:
                    return False
                for v19 in v18:
                    if not type(v19) is str:
                        return False
                    if v19 not in _C6:
                        if _C5(v19) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v19)
                if len(set(v18)) != len(v18):
                    return False
            v20 = v14.get('optional', _MISSING)
            if v20 is not _MISSING:
                if not type(v20) is bool:
                    return False
    v21 = data.get('nominal', _MISSING)
    if v21 is not _MISSING:
        if not type(v21) is dict:
            return False
        for v23 in v21.values():
            if not type(v23) is str:
                return False
            if v23 not in _C2:
                if _C1(v23) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v23)
        for v24 in v21:
            if not type(v24) is str:
                return False
            if v24 not in _C2:
                if _C1(v24) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v24)
    v25 = data.get('simulation', _MISSING)
    if v25 is not _MISSING:
        if not type(v25) is dict:
            return False
        if not v25.keys() <= _C7:
            return False
        v26 = v25.get('loops', _MISSING)
        if v26 is _MISSING:
            return False
        if not type(v26) is list:
            return False
        if len(v26) < 1:
            return False
        for v27 in v26:
            if not type(v27) is dict:
                return False
            if not v27.keys() <= _C8:
                return False
            v28 = v27.get('name', _MISSING)
            if v28 is _MISSING:
                return False
            if not type(v28) is str:
                return False
            if v28 not in _C2:
                if _C1(v28) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v28)
            v29 = v27.get('forward', _MISSING)
            if v29 is _MISSING:
                return False
            if not type(v29) is list:
                return False
            if len(v29) < 1:
                return False
            for v30 in v29:
                if not type(v30) is str:
                    return False
                if v30 not in _C2:
                    if _C1(v30) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v30)
            if len(set(v29)) != len(v29):
                return False
            v31 = v27.get('plant', _MISSING)
            if v31 is _MISSING:
                return False
            if not type(v31) is dict:
                return False
            if ((not ('transfer_function' not in v31)) + (not ('state_space' not in v31))) != 1:
                return False
            if not v31.keys() <= _C9:
                return False
            v32 = v31.get('transfer_function', _MISSING)
            if v32 is not _MISSING:
                if not type(v32) is dict:
                    return False
                if not v32.keys() <= _C10:
                    return False
                v33 = v32.get('num', _MISSING)
                if v33 is _MISSING:
                    return False
                if not type(v33) is list:
                    return False
                if len(v33) < 1:
                    return False
                for v34 in v33:
                    if not type(v34) in _NUMBER:
                        return False
                v35 = v32.get('den', _MISSING)
                if v35 is _MISSING:
                    return False
                if not type(v35) is list:
                    return False
                if len(v35) < 1:
                    return False
                for v36 in v35:
                    if not type(v36) in _NUMBER:
                        return False
            v37 = v31.get('state_space', _MISSING)
            if v37 is not _MISSING:
                if not type(v37) is dict:
                    return False
                if not v37.keys() <= _C11:
                    return False
                v38 = v37.get('A', _MISSING)
                if v38 is _MISSING:
                    return False
                if not type(v38) is list:
                    return False
                if len(v38) < 1:
                    return False
                for v39 in v38:
                    if not type(v39) is list:
                        return False
                    if len(v39) < 1:
                        return False
                    for v40 in v39:
                        if not type(v40) in _NUMBER:
                            return False
                v41 = v37.get('B', _MISSING)
                if v41 is _MISSING:
                    return False
                if not type(v41) is list:
                    return False
                if len(v41) < 1:
                    return False
                for v42 in v41:
                    if not type(v42) is list:
                        return False
                    if len(v42) < 1:
                        return False
                    for v43 in v42:
                        if not type(v43) in _NUMBER:
                            return False
                v44 = v37.get('C', _MISSING)
                if v44 is _MISSING:
                    return False
                if not type(v44) is list:
                    return False
                if len(v44) < 1:
                    return False
                for v45 in v44:
                    if not type(v45) is list:
                        return False
                    if len(v45) < 1:
                        return False
                    for v46 in v45:
                        if not type(v46) in _NUMBER:
                            return False
                v47 = v37.get('D', _MISSING)
                if v47 is _MISSING:
                    return False
                if not type(v47) is list:
                    return False
                if len(v47) < 1:
                    return False
                for v48 in v47:
                    if not type(v48) is list:
                        return False
                    if len(v48) < 1:
                        return False
                    for v49 in v48:
                        if not type(v49) in _NUMBER:
                            return False
            v50 = v31.get('delay', _MISSING)
            if v50 is not _MISSING:
                if not type(v50) in _NUMBER:
                    return False
                if v50 < 0:
                    return False
            v51 = v27.get('feedback', _MISSING)
            if v51 is not _MISSING:
                if not type(v51) is list:
                    return False
                for v52 in v51:
                    if not type(v52) is str:
                        return False
                    if v52 not in _C2:
                        if _C1(v52) is None:
                            return False
                        if len(_C2) < 100000:
                            _C2.add(v52)
                if len(set(v51)) != len(v51):
                    return False
        v53 = v25.get('reference', _MISSING)
        if v53 is not _MISSING:
            if not type(v53) in _NUMBER:
                return False
            if v53 <= 0:
                return False
        v54 = v25.get('duration', _MISSING)
        if v54 is _MISSING:
            return False
        if not type(v54) in _NUMBER:
            return False
        if v54 <= 0:
            return False
        v55 = v25.get('requirements', _MISSING)
        if v55 is not _MISSING:
            if not type(v55) is dict:
                return False
            if not v55.keys() <= _C12:
                return False
            v56 = v55.get('settling_time', _MISSING)
            if v56 is not _MISSING:
                if not type(v56) in _NUMBER:
                    return False
                if v56 < 0:
                    return False
            v57 = v55.get('steady_state_error', _MISSING)
            if v57 is not _MISSING:
                if not type(v57) in _NUMBER:
                    return False
                if v57 < 0:
                    return False
            v58 = v55.get('overshoot', _MISSING)
            if v58 is not _MISSING:
                if not type(v58) in _NUMBER:
                    return False
                if v58 < 0:
                    return False
    return True


VALIDATE = validate
