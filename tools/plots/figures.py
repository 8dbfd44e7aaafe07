"""What every chart script here does last: the title, a tight layout, the PNG written and said."""


def save(fig, title, path, dpi=90):
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    print("wrote", path)
    return 0
